#include "knitforge/sim/cloth_scene.h"

#include <cmath>
#include <filesystem>

#include <fmt/core.h>

#include "knitforge/sim/material_json.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Reader {
  std::string where;
  std::string base_dir;

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InvalidInput(fmt::format("{}: '{}' {}", where, field, what));
  }
  double number(const json& j, const std::string& field) const {
    if (!j.is_number()) fail(field, fmt::format("must be a number (got {})", j.dump()));
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(field, "must be finite");
    return v;
  }
  double positive(const json& j, const std::string& field) const {
    const double v = number(j, field);
    if (!(v > 0)) fail(field, fmt::format("must be positive (got {})", v));
    return v;
  }
  double non_negative(const json& j, const std::string& field) const {
    const double v = number(j, field);
    if (!(v >= 0)) fail(field, fmt::format("must be >= 0 (got {})", v));
    return v;
  }
  int integer(const json& j, const std::string& field, int lo, int hi) const {
    if (!j.is_number_integer()) fail(field, fmt::format("must be an integer (got {})", j.dump()));
    const auto v = j.get<int64_t>();
    if (v < lo || v > hi) fail(field, fmt::format("must be in [{}, {}] (got {})", lo, hi, v));
    return static_cast<int>(v);
  }
  Vec3 vec3(const json& j, const std::string& field) const {
    if (!j.is_array() || j.size() != 3) fail(field, fmt::format("must be [x, y, z] (got {})", j.dump()));
    return Vec3(number(j[0], field + "[0]"), number(j[1], field + "[1]"), number(j[2], field + "[2]"));
  }
  Vec3 direction(const json& j, const std::string& field) const {
    const Vec3 v = vec3(j, field);
    if (!(v.norm() > 0)) fail(field, "must be a non-zero direction");
    return v.normalized();
  }
  std::string string(const json& j, const std::string& field) const {
    if (!j.is_string() || j.get<std::string>().empty()) fail(field, "must be a non-empty string");
    return j.get<std::string>();
  }
  std::string path(const json& j, const std::string& field) const {
    const std::string p = string(j, field);
    return base_dir.empty() || fs::path(p).is_absolute() ? p : (fs::path(base_dir) / p).string();
  }
  std::string units(const json& j, const std::string& field) const {
    const std::string u = string(j, field);
    if (u != "mm" && u != "cm" && u != "m") fail(field, fmt::format("must be mm, cm or m (got '{}')", u));
    return u;
  }
  std::vector<int> indices(const json& j, const std::string& field) const {
    if (!j.is_array()) fail(field, "must be an array of vertex indices");
    std::vector<int> out;
    for (size_t k = 0; k < j.size(); ++k) out.push_back(integer(j[k], fmt::format("{}[{}]", field, k), 0, 1 << 30));
    return out;
  }
  [[noreturn]] void unknown(const std::string& field, const std::string& known) const {
    throw InvalidInput(fmt::format("{}: unknown field '{}' (fields: {})", where, field, known));
  }
};

struct Field {
  const char* name;
  double* value;
};

std::vector<Field> arm_fields(ArmMotionParams& a) {
  return {{"upper_length_mm", &a.upper_length_mm}, {"forearm_length_mm", &a.forearm_length_mm},
          {"upper_radius_mm", &a.upper_radius_mm}, {"forearm_radius_mm", &a.forearm_radius_mm},
          {"max_angle_deg", &a.max_angle_deg},     {"body_edge_mm", &a.body_edge_mm},
          {"sleeve_edge_mm", &a.sleeve_edge_mm},   {"clearance_mm", &a.clearance_mm},
          {"sleeve_start_mm", &a.sleeve_start_mm}, {"wrist_margin_mm", &a.wrist_margin_mm},
          {"transition_mm", &a.transition_mm}};
}

std::vector<Field> leg_fields(LegMotionParams& l) {
  return {{"thigh_length_mm", &l.thigh_length_mm}, {"shin_length_mm", &l.shin_length_mm},
          {"thigh_radius_mm", &l.thigh_radius_mm}, {"shin_radius_mm", &l.shin_radius_mm},
          {"max_angle_deg", &l.max_angle_deg},     {"body_edge_mm", &l.body_edge_mm},
          {"legging_edge_mm", &l.legging_edge_mm}, {"clearance_mm", &l.clearance_mm},
          {"waist_margin_mm", &l.waist_margin_mm}, {"ankle_margin_mm", &l.ankle_margin_mm},
          {"transition_mm", &l.transition_mm}};
}

// The fields of a built-in limb ("arm" or "leg"), then `check` (the limb's
// own checks, named with the scene).
template <class Check>
void read_limb(const Reader& r, const json& j, const std::string& what, const std::vector<Field>& fields,
               Check check) {
  if (!j.is_object()) r.fail(what, fmt::format("must be an object of {} parameters", what));
  for (const auto& [key, value] : j.items()) {
    bool found = false;
    for (const Field& f : fields) {
      if (key == f.name) {
        *f.value = r.number(value, what + "." + key);
        found = true;
      }
    }
    if (!found) {
      std::string known;
      for (const Field& f : fields) known += (known.empty() ? "" : ", ") + std::string(f.name);
      r.unknown(what + "." + key, known);
    }
  }
  try {
    check();
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: '{}': {}", r.where, what, e.what()));
  }
}

json fields_json(const std::vector<Field>& fields) {
  json j = json::object();
  for (const Field& f : fields) j[f.name] = *f.value;
  return j;
}

void read_garment(const Reader& r, const json& j, ClothScene& s) {
  if (!j.is_object()) r.fail("garment", "must be an object with \"mesh\" and a course direction");
  for (const auto& [key, value] : j.items()) {
    if (key == "mesh") {
      s.garment_mesh = r.path(value, "garment.mesh");
    } else if (key == "stitch_mesh") {
      s.garment_stitch_mesh = r.path(value, "garment.stitch_mesh");
    } else if (key == "design") {
      s.garment_design = r.path(value, "garment.design");
    } else if (key == "stitch_size") {
      s.garment_stitch_size = r.string(value, "garment.stitch_size");
    } else if (key == "units") {
      s.garment_units = r.units(value, "garment.units");
    } else if (key == "course_direction") {
      s.course_direction = r.direction(value, "garment.course_direction");
    } else if (key == "course_axis") {
      if (!value.is_object() || !value.contains("point") || !value.contains("direction") || value.size() != 2)
        r.fail("garment.course_axis", "must be {\"point\": [x, y, z], \"direction\": [x, y, z]}");
      s.course_axis = std::pair(r.vec3(value["point"], "garment.course_axis.point"),
                                r.direction(value["direction"], "garment.course_axis.direction"));
    } else if (key == "material") {
      s.materials = {value.is_string() ? read_material_json(r.path(value, "garment.material"))
                                       : material_from_json(value, r.where + ": garment.material")};
    } else if (key == "materials") {
      if (!value.is_array() || value.empty()) r.fail("garment.materials", "must be a non-empty array of materials");
      s.materials.clear();
      for (size_t k = 0; k < value.size(); ++k) {
        const std::string f = fmt::format("garment.materials[{}]", k);
        s.materials.push_back(value[k].is_string() ? read_material_json(r.path(value[k], f))
                                                   : material_from_json(value[k], r.where + ": " + f));
      }
    } else if (key == "face_materials") {
      s.face_materials = r.indices(value, "garment.face_materials");
    } else if (key == "clearance_mm") {
      s.dress_clearance_mm = r.positive(value, "garment.clearance_mm");
      if (s.dress_clearance_mm > 10) r.fail("garment.clearance_mm", "must be at most 10 mm");
    } else {
      r.unknown("garment." + key,
                "mesh, stitch_mesh, design, stitch_size, units, course_direction, course_axis, material, materials, "
                "face_materials, clearance_mm");
    }
  }
  const int sources = int(!s.garment_mesh.empty()) + int(!s.garment_stitch_mesh.empty()) + int(!s.garment_design.empty());
  if (sources != 1) {
    r.fail("garment", "needs exactly one of \"mesh\" (a triangle mesh file: .obj, .ply, .off, .stl), "
                      "\"stitch_mesh\" (a stitch mesh PLY or a knitting map) and \"design\" (a design command's "
                      "output directory)");
  }
  if (s.garment_mesh.empty()) {  // a stitch mesh: its stitches give the courses, per-yarn materials
    if (s.course_direction || s.course_axis)
      r.fail(s.course_direction ? "garment.course_direction" : "garment.course_axis",
             "is for a triangle-mesh garment; a stitch mesh has its own courses (remove it)");
    if (!s.face_materials.empty())
      r.fail("garment.face_materials", "is for a triangle-mesh garment; a stitch mesh's yarn y takes materials[y]");
    if (s.garment_units != "mm") r.fail("garment.units", "must be mm for a stitch mesh (stitch meshes are in mm)");
  } else {
    if (!s.garment_stitch_size.empty())
      r.fail("garment.stitch_size", "goes with \"stitch_mesh\" or \"design\" (the stitches' rest size)");
    if (s.course_direction.has_value() == s.course_axis.has_value())
      r.fail("garment", "needs exactly one of \"course_direction\" and \"course_axis\" (the knit's course direction)");
  }
  for (size_t k = 0; k < s.face_materials.size(); ++k) {
    if (s.face_materials[k] >= static_cast<int>(s.materials.size())) {
      r.fail(fmt::format("garment.face_materials[{}]", k),
             fmt::format("is material {}, but there are {} materials", s.face_materials[k], s.materials.size()));
    }
  }
}

void read_body(const Reader& r, const json& j, ClothScene& s) {
  if (!j.is_object()) r.fail("body", "must be an object with \"mesh\" or \"frames\"");
  for (const auto& [key, value] : j.items()) {
    if (key == "mesh") {
      s.body_mesh = r.path(value, "body.mesh");
    } else if (key == "frames") {
      if (!value.is_array() || value.empty()) r.fail("body.frames", "must be a non-empty array of mesh files");
      for (size_t k = 0; k < value.size(); ++k) s.body_frames.push_back(r.path(value[k], fmt::format("body.frames[{}]", k)));
    } else if (key == "animation") {
      s.body_animation = r.path(value, "body.animation");
    } else if (key == "mesh_name") {
      s.body_mesh_name = r.string(value, "body.mesh_name");
    } else if (key == "animation_name") {
      s.body_animation_name = r.string(value, "body.animation_name");
    } else if (key == "units") {
      s.body_units = r.units(value, "body.units");
    } else {
      r.unknown("body." + key, "mesh, frames, animation, mesh_name, animation_name, units");
    }
  }
  if (int(!s.body_mesh.empty()) + int(!s.body_frames.empty()) + int(!s.body_animation.empty()) != 1) {
    r.fail("body", "needs exactly one of \"mesh\" (a static body), \"frames\" (one mesh per frame) and "
                   "\"animation\" (a .glb or .gltf with a morph-target or node animation)");
  }
  if (s.body_animation.empty() && (!s.body_mesh_name.empty() || !s.body_animation_name.empty()))
    r.fail(s.body_mesh_name.empty() ? "body.animation_name" : "body.mesh_name", "goes with \"animation\" (a glTF file)");
}

}  // namespace

const std::vector<std::string>& builtin_cloth_scene_names() {
  static const std::vector<std::string> names = {"sleeve", "legging"};
  return names;
}

ClothScene cloth_scene_from_json(const json& j, const std::string& where, const std::string& base_dir) {
  const Reader r{where, base_dir};
  if (!j.is_object()) throw InvalidInput(fmt::format("{}: a cloth scene must be a JSON object", where));
  ClothScene s;
  s.where = where;
  if (j.contains("builtin")) {
    s.builtin = r.string(j["builtin"], "builtin");
    bool known = false;
    std::string names;
    for (const std::string& n : builtin_cloth_scene_names()) {
      known = known || n == s.builtin;
      names += (names.empty() ? "" : ", ") + n;
    }
    if (!known) r.fail("builtin", fmt::format("'{}' is not a built-in scene (known: {})", s.builtin, names));
    if (j.contains("garment") || j.contains("body") || j.contains("attach_within_mm"))
      r.fail("builtin", "brings its own garment, body and attachments; remove \"garment\", \"body\", \"attach_within_mm\"");
    // The sleeve's rings are attached; the frame rate and length make one smooth bend.
  }
  bool has_garment = false, has_body = false;
  for (const auto& [key, value] : j.items()) {
    if (key == "builtin") continue;
    if (key == "arm") {
      if (s.builtin != "sleeve") r.fail("arm", "is a parameter of the built-in sleeve (\"builtin\": \"sleeve\")");
      read_limb(r, value, "arm", arm_fields(s.arm), [&] {
        (void)arm_upper_vertex_count(s.arm);
        (void)arm_sleeve_mesh(s.arm).mesh.num_vertices();
      });
    } else if (key == "leg") {
      if (s.builtin != "legging") r.fail("leg", "is a parameter of the built-in legging (\"builtin\": \"legging\")");
      read_limb(r, value, "leg", leg_fields(s.leg), [&] { (void)legging_mesh(s.leg).mesh.num_vertices(); });
    } else if (key == "garment") {
      read_garment(r, value, s);
      has_garment = true;
    } else if (key == "body") {
      read_body(r, value, s);
      has_body = true;
    } else if (key == "frames") {
      s.frames = r.integer(value, key, 1, 100000);
      s.frames_given = true;
    } else if (key == "frame_rate_hz") {
      s.frame_rate_hz = r.positive(value, key);
    } else if (key == "substeps") {
      s.substeps = r.integer(value, key, 1, 1000);
    } else if (key == "friction") {
      s.friction = r.non_negative(value, key);
    } else if (key == "gravity_mm_s2") {
      s.gravity_mm_s2 = r.vec3(value, key);
    } else if (key == "pin") {
      s.pinned = r.indices(value, key);
    } else if (key == "attach") {
      s.attached = r.indices(value, key);
    } else if (key == "attach_within_mm") {
      s.attach_within_mm = r.non_negative(value, key);
    } else if (key == "contact_distance_mm") {
      s.contact_distance_mm = r.positive(value, key);
    } else if (key == "sliding_distance_mm") {
      s.sliding_distance_mm = r.positive(value, key);
    } else if (key == "newton") {
      if (!value.is_object()) r.fail(key, "must be {\"max_iterations\": N, \"force_tolerance_mn\": F}");
      for (const auto& [k2, v2] : value.items()) {
        if (k2 == "max_iterations")
          s.max_newton_iterations = r.integer(v2, "newton.max_iterations", 1, 100000);
        else if (k2 == "force_tolerance_mn")
          s.force_tolerance_mn = r.positive(v2, "newton.force_tolerance_mn");
        else
          r.unknown("newton." + k2, "max_iterations, force_tolerance_mn");
      }
    } else if (key == "solver") {
      if (value == "preview") {
        s.preview = true;
      } else if (value == "implicit") {
        s.preview = false;
      } else {
        r.fail(key, "must be \"implicit\" (the default) or \"preview\"");
      }
    } else if (key == "preview") {
      if (!value.is_object()) r.fail(key, "must be {\"max_iterations\": N}");
      for (const auto& [k2, v2] : value.items()) {
        if (k2 == "max_iterations")
          s.preview_iterations = r.integer(v2, "preview.max_iterations", 1, 100000);
        else
          r.unknown("preview." + k2, "max_iterations");
      }
    } else {
      r.unknown(key,
                "builtin, arm, leg, garment, body, frames, frame_rate_hz, substeps, friction, gravity_mm_s2, pin, attach, "
                "attach_within_mm, contact_distance_mm, sliding_distance_mm, newton, solver, preview");
    }
  }
  if (s.builtin.empty()) {
    if (!has_garment) r.fail("garment", "is missing (or name a built-in scene: \"builtin\": \"sleeve\" or \"legging\")");
    if (!has_body) r.fail("body", "is missing (a mesh, one mesh per frame, or a glTF animation)");
    if (!s.body_frames.empty() && static_cast<int>(s.body_frames.size()) != s.frames + 1) {
      r.fail("body.frames", fmt::format("has {} meshes; a run of {} frames needs frames + 1 = {} (frame 0 is the start)",
                                        s.body_frames.size(), s.frames, s.frames + 1));
    }
  } else if (!s.pinned.empty() || !s.attached.empty()) {
    r.fail(s.pinned.empty() ? "attach" : "pin", "is set by the built-in scene (its first and last rings)");
  }
  if (s.contact_distance_mm > 10) {
    r.fail("contact_distance_mm", fmt::format("{} mm is more than 10 mm; the barrier acts within this distance, "
                                              "keep it below the garment's edge length",
                                              s.contact_distance_mm));
  }
  return s;
}

ClothScene read_cloth_scene(const std::string& path) {
  return cloth_scene_from_json(read_json_file(path, "scene file"), path, fs::path(path).parent_path().string());
}

ClothScene builtin_cloth_scene(const std::string& name) {
  return cloth_scene_from_json(json{{"builtin", name}}, "built-in " + name);
}

json cloth_scene_to_json(const ClothScene& s) {
  json j;
  if (!s.builtin.empty()) {
    j["builtin"] = s.builtin;
    ClothScene copy = s;  // the field tables point into it
    if (s.builtin == "legging") j["leg"] = fields_json(leg_fields(copy.leg));
    else j["arm"] = fields_json(arm_fields(copy.arm));
  } else {
    json g = {{"units", s.garment_units}};
    if (!s.garment_mesh.empty()) g["mesh"] = s.garment_mesh;
    if (!s.garment_stitch_mesh.empty()) g["stitch_mesh"] = s.garment_stitch_mesh;
    if (!s.garment_design.empty()) g["design"] = s.garment_design;
    if (!s.garment_stitch_size.empty()) g["stitch_size"] = s.garment_stitch_size;
    if (s.course_direction) g["course_direction"] = {s.course_direction->x(), s.course_direction->y(), s.course_direction->z()};
    if (s.course_axis) {
      const auto& [p, d] = *s.course_axis;
      g["course_axis"] = {{"point", {p.x(), p.y(), p.z()}}, {"direction", {d.x(), d.y(), d.z()}}};
    }
    json mats = json::array();
    for (const KnitMaterial& m : s.materials) mats.push_back(material_to_json(m));
    g["materials"] = mats;
    if (!s.face_materials.empty()) g["face_materials"] = s.face_materials;
    if (s.dress_clearance_mm > 0) g["clearance_mm"] = s.dress_clearance_mm;
    j["garment"] = g;
    if (!s.body_animation.empty()) {
      j["body"] = {{"animation", s.body_animation}, {"units", s.body_units}};
      if (!s.body_mesh_name.empty()) j["body"]["mesh_name"] = s.body_mesh_name;
      if (!s.body_animation_name.empty()) j["body"]["animation_name"] = s.body_animation_name;
    } else {
      j["body"] = s.body_frames.empty() ? json{{"mesh", s.body_mesh}, {"units", s.body_units}}
                                        : json{{"frames", s.body_frames}, {"units", s.body_units}};
    }
    j["pin"] = s.pinned;
    j["attach"] = s.attached;
    j["attach_within_mm"] = s.attach_within_mm;
  }
  j["frames"] = s.frames;
  j["frame_rate_hz"] = s.frame_rate_hz;
  j["substeps"] = s.substeps;
  j["friction"] = s.friction;
  j["gravity_mm_s2"] = {s.gravity_mm_s2.x(), s.gravity_mm_s2.y(), s.gravity_mm_s2.z()};
  j["contact_distance_mm"] = s.contact_distance_mm;
  j["sliding_distance_mm"] = s.sliding_distance_mm;
  j["newton"] = {{"max_iterations", s.max_newton_iterations}, {"force_tolerance_mn", s.force_tolerance_mn}};
  j["solver"] = s.preview ? "preview" : "implicit";
  j["preview"] = {{"max_iterations", s.preview_iterations}};
  return j;
}

}  // namespace knitforge
