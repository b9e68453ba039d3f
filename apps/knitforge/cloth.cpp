// knitforge cloth: a garment on a moving body by the fabric simulator
// (docs/sim.md, "Garments on a moving body"): a scene file or a built-in
// scene (a capsule arm bending inside a sleeve, a capsule leg bending inside a
// legging), written as an OBJ/PLY
// sequence, an animated glTF, per-frame stress and sliding, and a report page.
#include <algorithm>
#include <functional>
#include <filesystem>
#include <limits>
#include <optional>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/evaluate/scalar_colours.h"
#include "knitforge/io/gltf.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/png_image.h"
#include "knitforge/io/read_gltf_animation.h"
#include "knitforge/render/camera.h"
#include "knitforge/render/raster_preview.h"
#include "knitforge/report/report_html.h"
#include "knitforge/sim/cloth_scene.h"
#include "knitforge/sim/contact_candidates.h"
#include "knitforge/sim/dress_garment.h"
#include "knitforge/sim/kinematic_body.h"
#include "knitforge/sim/leg_motion.h"
#include "knitforge/sim/material_json.h"
#include "knitforge/sim/simulate_cloth.h"
#include "knitforge/util/timer.h"

namespace knitforge::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// What a scene becomes before the run: meshes loaded and checked.
struct LoadedScene {
  TriMesh garment;
  std::vector<Vec3> course;
  TriMesh body;
  std::vector<std::vector<Vec3>> body_frames;  // empty = static
  std::vector<int> pinned, attached;
  // Built-in scenes: the joint's angle per frame, its name in cloth.json
  // ("elbow_angle_deg"), and the signed distance to the true capsules.
  std::vector<double> joint_angle_deg;
  std::string angle_key, clearance_key;
  std::function<double(double angle_deg, const Vec3& x)> true_distance;
  // A stitch-mesh garment: its model (rest shape = every stitch at its
  // ideal size), and what it was made from.
  std::optional<SimModel> stitch_model;
  nlohmann::json garment_source;
  // garment.clearance_mm: the garment's start moved out of the body.
  std::optional<DressResult> dress;
};

// A stitch mesh (PLY or knitting map, relaxed as `relax` does) or a design
// directory's stitch_mesh.ply, with the stitch size of the scene, else of the
// design's report.json, else 3.5 x 2.8 mm; the model's triangles are the garment.
void load_stitch_garment(const ClothScene& s, LoadedScene& L) {
  std::string path = s.garment_stitch_mesh, stitch = s.garment_stitch_size, from = "scene";
  if (!s.garment_design.empty()) {
    path = (fs::path(s.garment_design) / "stitch_mesh.ply").string();
    if (!fs::is_regular_file(path)) {
      throw InvalidInput(fmt::format("{}: garment.design {}: not a design directory (no stitch_mesh.ply); give a "
                                     "design command's output directory, or \"stitch_mesh\"",
                                     s.where, s.garment_design));
    }
    const fs::path report = fs::path(s.garment_design) / "report.json";
    if (stitch.empty() && fs::exists(report)) {
      const json r = json::parse(read_text_file(report.string(), "design report"), nullptr, false);
      if (r.is_object() && r.contains("parameters") && r["parameters"].is_object() &&
          r["parameters"].contains("stitch_width_mm") && r["parameters"].contains("stitch_height_mm") &&
          r["parameters"]["stitch_width_mm"].is_number() && r["parameters"]["stitch_height_mm"].is_number()) {
        stitch = fmt::format("{}x{}", r["parameters"]["stitch_width_mm"].get<double>(),
                             r["parameters"]["stitch_height_mm"].get<double>());
        from = report.string();
      }
    }
  }
  if (stitch.empty()) {
    stitch = "3.5x2.8";
    from = "default";
  }
  KnitParams params;
  try {
    params = parse_stitch_size(stitch);
  } catch (const Error& e) {
    throw InvalidInput(fmt::format("{}: garment.stitch_size: {}", s.where, e.what()));
  }
  check_input_file(path);
  const StitchInput in = load_stitch_input(path);
  StitchMesh designed;
  if (in.is_map) {
    designed = relax_stitch_mesh(map_to_stitch_mesh_topology(in.map, params), params, RelaxOptions{}).mesh;
  } else {
    designed = in.mesh;
  }
  SimModelOptions mo;
  mo.materials = s.materials;
  L.stitch_model = build_sim_model(designed, params, mo);
  L.garment = L.stitch_model->triangles();
  L.garment_source = {{"stitch_mesh", path},
                      {"stitches", designed.num_stitches()},
                      {"stitch_width_mm", params.stitch_width},
                      {"stitch_height_mm", params.stitch_height},
                      {"stitch_size_from", from}};
}

// A glTF body: sampled at the frame times from the animation's first key
// (scene.frames set to the animation's length when the scene has none).
void load_gltf_body(ClothScene& s, LoadedScene& L, double max_work, int preview_rounds) {
  GltfReadOptions go;
  go.mesh_name = s.body_mesh_name;
  go.animation = s.body_animation_name;
  const GltfAnimatedMesh anim = read_gltf_animation(s.body_animation, go);
  const double length = anim.end_s - anim.start_s;
  const double fit = std::floor(length * s.frame_rate_hz + 1e-6);  // whole frames within the animation
  if (!s.frames_given && length > 0) {
    if (fit > 100000) {
      throw InvalidInput(fmt::format("{}: body.animation {}: {:.4g} s at {} Hz are more than 100000 frames; set "
                                     "\"frames\"",
                                     s.where, s.body_animation, length, s.frame_rate_hz));
    }
    s.frames = std::max(1, static_cast<int>(fit));
  }
  const double run = s.frames / s.frame_rate_hz;
  if (length > 0 && run > length + 1e-6) {
    throw InvalidInput(fmt::format(
        "{}: body.animation {}: the animation '{}' lasts {:.4g} s ({:.4g} to {:.4g} s); {} frames at {} Hz need "
        "{:.4g} s: set \"frames\" to at most {} (or omit it), or lower frame_rate_hz",
        s.where, s.body_animation, anim.animation_name, length, anim.start_s, anim.end_s, s.frames, s.frame_rate_hz,
        run, fit));
  }
  check_cloth_work(L.garment.num_vertices(), s.frames, s.substeps, max_work, preview_rounds);  // before the frames are made
  const double scale = unit_scale(s.body_units);
  L.body.faces = anim.faces;
  for (int f = 0; f <= s.frames; ++f) {
    std::vector<Vec3> p = gltf_positions_at(anim, anim.start_s + f / s.frame_rate_hz);
    for (Vec3& x : p) x *= scale;
    if (f == 0) L.body.vertices = p;
    L.body_frames.push_back(std::move(p));
  }
}

LoadedScene load_scene(ClothScene& s, double max_work, int preview_rounds) {
  LoadedScene L;
  if (s.builtin == "sleeve" || s.builtin == "legging") {
    const bool arm = s.builtin == "sleeve";
    const SleeveMesh tube = arm ? arm_sleeve_mesh(s.arm) : legging_mesh(s.leg);
    L.garment = tube.mesh;
    L.course = tube.course_directions;
    L.attached = tube.attached;
    auto body = [&](double angle) { return arm ? arm_body_mesh(s.arm, angle) : leg_body_mesh(s.leg, angle); };
    L.body = body(0.0);
    for (int f = 0; f <= s.frames; ++f) {
      L.joint_angle_deg.push_back(arm ? arm_elbow_angle_deg(s.arm, f, s.frames) : leg_knee_angle_deg(s.leg, f, s.frames));
      L.body_frames.push_back(body(L.joint_angle_deg.back()).vertices);
    }
    L.angle_key = arm ? "elbow_angle_deg" : "knee_angle_deg";
    L.clearance_key = arm ? "min_arm_clearance_mm" : "min_leg_clearance_mm";
    const ArmMotionParams a = s.arm;
    const LegMotionParams l = s.leg;
    L.true_distance = [arm, a, l](double angle, const Vec3& x) {
      return arm ? arm_signed_distance(a, angle, x) : leg_signed_distance(l, angle, x);
    };
    return L;
  }
  if (s.garment_mesh.empty()) {
    load_stitch_garment(s, L);
  } else {
    L.garment = load_surface(s.garment_mesh, s.garment_units);
    L.garment_source = {{"mesh", s.garment_mesh}};
  }
  const int nf = L.garment.num_faces(), nv = L.garment.num_vertices();
  if (!s.face_materials.empty() && static_cast<int>(s.face_materials.size()) != nf) {
    throw InvalidInput(fmt::format("{}: garment.face_materials has {} entries, the garment {} has {} faces", s.where,
                                   s.face_materials.size(), s.garment_mesh, nf));
  }
  if (L.stitch_model) {
    // courses from the stitches
  } else if (s.course_direction) {
    L.course = {*s.course_direction};
  } else {
    const auto& [point, dir] = *s.course_axis;
    for (const auto& f : L.garment.faces) {
      const Vec3 c = (L.garment.vertices[f[0]] + L.garment.vertices[f[1]] + L.garment.vertices[f[2]]) / 3.0;
      L.course.push_back(dir.cross(c - point));  // build_sim_model refuses a course normal to its face
    }
  }
  if (!s.body_mesh.empty()) {
    L.body = load_surface(s.body_mesh, s.body_units);
  } else if (!s.body_animation.empty()) {
    load_gltf_body(s, L, max_work, preview_rounds);
  } else {
    for (size_t k = 0; k < s.body_frames.size(); ++k) {
      TriMesh m = load_surface(s.body_frames[k], s.body_units);
      if (k == 0) {
        L.body = m;
      } else if (m.faces != L.body.faces) {
        throw InvalidInput(fmt::format("{}: body frame {} ({}) has other faces than frame 0 ({}); every frame must be "
                                       "the same mesh, moved",
                                       s.where, k, s.body_frames[k], s.body_frames[0]));
      }
      L.body_frames.push_back(std::move(m.vertices));
    }
  }
  for (const auto* list : {&s.pinned, &s.attached}) {
    for (int v : *list) {
      if (v >= nv) {
        throw InvalidInput(fmt::format("{}: '{}' names vertex {}, the garment has {} (0..{})", s.where,
                                       list == &s.pinned ? "pin" : "attach", v, nv, nv - 1));
      }
    }
  }
  L.pinned = s.pinned;
  L.attached = s.attached;
  const std::vector<Vec3>* start = &L.garment.vertices;
  std::optional<KinematicBody> body;  // the body at the start, for dressing and attaching
  if (s.dress_clearance_mm > 0 || s.attach_within_mm > 0) body.emplace(L.body);
  if (s.dress_clearance_mm > 0) {
    DressOptions d;
    d.clearance_mm = s.dress_clearance_mm;
    try {
      L.dress = dress_garment(*body, L.garment.vertices, s.pinned, d);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: garment.clearance_mm: {}", s.where, e.what()));
    }
    start = &L.dress->positions;
  }
  if (s.attach_within_mm > 0) {
    Eigen::VectorXd x(3 * static_cast<Eigen::Index>(nv));
    for (int v = 0; v < nv; ++v) x.segment<3>(3 * v) = (*start)[static_cast<size_t>(v)];
    for (const ContactPair& c : find_contact_candidates(*body, x, s.attach_within_mm)) L.attached.push_back(c.vertex);
  }
  std::sort(L.attached.begin(), L.attached.end());
  L.attached.erase(std::unique(L.attached.begin(), L.attached.end()), L.attached.end());
  for (int v : L.attached) {
    if (std::find(s.pinned.begin(), s.pinned.end(), v) != s.pinned.end()) {
      throw InvalidInput(fmt::format("{}: vertex {} is both pinned and attached; choose one", s.where, v));
    }
  }
  return L;
}

std::vector<Rgb> to_rgb(const std::vector<Rgb8>& c) {
  std::vector<Rgb> out(c.size());
  for (size_t i = 0; i < c.size(); ++i) out[i] = {c[i][0], c[i][1], c[i][2]};
  return out;
}

// Values rounded to 4 significant digits of the field's largest magnitude (compact JSON).
json rounded(const std::vector<double>& v) {
  double top = 0;
  for (double x : v) top = std::max(top, std::abs(x));
  const double q = top > 0 ? std::pow(10.0, std::floor(std::log10(top)) - 3) : 1.0;
  json out = json::array();
  for (double x : v) out.push_back(std::round(x / q) * q);
  return out;
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The preview's wall seconds under their own names (ClothFrame::seconds).
json preview_timings_json(const NewtonTimings& t) {
  return {{"assembly_and_factor_s", t.factor}, {"rounds_s", t.evaluate}, {"contacts_s", t.max_step}};
}

constexpr const char* kPreviewPenetration =
    "preview (projective dynamics): contact is a projection onto the tangent planes of the body parts each vertex "
    "was near at its step's start, and every move passes the implicit solver's collision-free check (a step is "
    "split while the body would pass through the fabric), so no vertex reaches the body mesh; min_distance_mm is "
    "the smallest unsigned distance of a free vertex to the body mesh over all frames; for the built-in arm (leg), "
    "min_arm_clearance_mm (min_leg_clearance_mm) is the smallest signed distance of a free vertex to the true "
    "capsules (negative inside; the mesh is inscribed, so down to minus its chord sag)";

}  // namespace

void add_cloth_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "cloth",
      "A garment on a moving body by the fabric simulator (docs/sim.md): a scene file (docs/formats.md) or a "
      "built-in scene (--builtin sleeve: a capsule arm bending at the elbow inside a knitted sleeve; --builtin "
      "legging: a capsule leg bending at the knee inside a knitted legging); writes the "
      "animation (OBJ/PLY sequence, animation.glb), per-frame stress and sliding, cloth.json and report.html");
  struct Opts {
    std::string scene, builtin, outdir;
    int frames = 0, substeps = 0;
    int quasi_newton = ClothOptions{}.quasi_newton.max_iterations;
    int preview_iterations = 0;  // 0: the scene's
    double max_work = 0;         // 0: the solver's default limit
    bool json = false, preview_flag = false, implicit_flag = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("scene", o->scene, "Scene file (JSON, docs/formats.md \"Cloth scene\")");
  cmd->add_option("--builtin", o->builtin, "A built-in scene instead of a file: sleeve, legging");
  cmd->add_option("-o,--output", o->outdir, "Output directory")->required();
  cmd->add_option("--frames", o->frames, "Frames to simulate (overrides the scene's)")->check(CLI::Range(1, 100000));
  cmd->add_option("--substeps", o->substeps, "Time steps per frame (overrides the scene's)")->check(CLI::Range(1, 1000));
  cmd->add_option("--quasi-newton", o->quasi_newton,
                  "L-BFGS iterations allowed per time step before its Newton solve (0 = Newton alone; docs/sim.md, "
                  "\"Solver\")")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  auto* preview_opt = cmd->add_flag("--preview", o->preview_flag,
               "The fast preview instead of the implicit solver: projective dynamics on a quadratic surrogate of the "
               "material, contact by projection (docs/sim.md, \"The fast preview\"): 30-40 times faster, never "
               "inside the body, but not the FEM answer (about 5 mm RMS from it on the built-in sleeve); a scene asks "
               "for it with \"solver\": \"preview\"");
  cmd->add_flag("--implicit", o->implicit_flag,
                "The implicit solver even where the scene asks for the preview")
      ->excludes(preview_opt);
  cmd->add_option("--preview-iterations", o->preview_iterations,
                  "The preview's local-global rounds per time step at most (default: the scene's \"preview\": "
                  "{\"max_iterations\"}, 30)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--max-work", o->max_work,
                  fmt::format("Refuse runs of more garment vertices x frames x substeps than this (x rounds / 30 for "
                              "the preview; default {:g}, about 40 minutes of the implicit solver, or {:g} for the "
                              "preview, about 15 minutes)",
                              kMaxClothWork, kMaxPreviewWork))
      ->check(positive_number());
  cmd->add_flag("--json", o->json, "Also print the summary (report.json) on stdout");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const Timer all;
      if (o->scene.empty() == o->builtin.empty()) {
        throw UsageError("cloth: give a scene file or --builtin NAME (one of them)");
      }
      if (!o->scene.empty()) check_input_file(o->scene);
      check_output_dir("--output", o->outdir, o->scene.empty() ? std::vector<std::string>{}
                                                                : std::vector<std::string>{o->scene});
      ClothScene scene = o->builtin.empty() ? read_cloth_scene(o->scene) : builtin_cloth_scene(o->builtin);
      if (o->frames > 0) {
        if (!scene.body_frames.empty() && o->frames != scene.frames) {
          throw UsageError(fmt::format("--frames {}: the scene's body has {} frames; --frames only changes scenes "
                                       "with a static or built-in body",
                                       o->frames, scene.frames));
        }
        scene.frames = o->frames;
        scene.frames_given = true;
      }
      if (o->substeps > 0) scene.substeps = o->substeps;
      if (o->preview_flag) scene.preview = true;
      if (o->implicit_flag) scene.preview = false;
      if (o->preview_iterations > 0) {
        if (!scene.preview) throw UsageError("cloth: --preview-iterations applies to the preview only (--preview)");
        scene.preview_iterations = o->preview_iterations;
      }
      const bool preview = scene.preview;
      const int rounds = preview ? scene.preview_iterations : 0;
      const double max_work = o->max_work > 0 ? o->max_work : preview ? kMaxPreviewWork : kMaxClothWork;
      const LoadedScene L = load_scene(scene, max_work, rounds);  // a glTF body may set scene.frames
      check_cloth_work(L.garment.num_vertices(), scene.frames, scene.substeps, max_work, rounds);

      SimModelOptions mo;
      mo.materials = scene.materials;
      SimModel model = L.stitch_model ? *L.stitch_model : build_sim_model(L.garment, L.course, scene.face_materials, mo);
      if (L.dress) {
        model.rest_positions = L.dress->positions;  // the start; the rest shape stays the model's
        note(fmt::format("cloth: dressed: {} garment vertices moved out to {} mm from the body ({} were inside or "
                         "on it, the deepest {:.2f} mm; largest move {:.2f} mm)",
                         L.dress->moved, scene.dress_clearance_mm, L.dress->inside, L.dress->deepest_mm,
                         L.dress->largest_move_mm));
      }
      model.pinned = L.pinned;
      model.pinned.insert(model.pinned.end(), L.attached.begin(), L.attached.end());
      std::sort(model.pinned.begin(), model.pinned.end());
      model.pinned.erase(std::unique(model.pinned.begin(), model.pinned.end()), model.pinned.end());

      ClothOptions co;
      co.frames = scene.frames;
      co.frame_rate_hz = scene.frame_rate_hz;
      co.substeps = scene.substeps;
      co.gravity_mm_s2 = scene.gravity_mm_s2;
      co.contact.friction = scene.friction;
      co.contact.distance_mm = scene.contact_distance_mm;
      co.sliding_distance_mm = scene.sliding_distance_mm;
      co.newton.max_iterations = scene.max_newton_iterations;
      co.newton.force_tolerance_mn = scene.force_tolerance_mn;
      co.quasi_newton.max_iterations = o->quasi_newton;
      co.solver = preview ? ClothSolver::Preview : ClothSolver::Implicit;
      co.preview.max_iterations = scene.preview_iterations;
      const char* solver_name = preview ? "preview" : "implicit";
      note(fmt::format("cloth: {} ({} vertices, {} triangles; body {} vertices), {} frames at {} Hz x {} substeps, {} "
                       "solver ...",
                       scene.where, model.num_vertices(), model.num_elements(), L.body.num_vertices(), co.frames,
                       co.frame_rate_hz, co.substeps, solver_name));
      const Timer sim_timer;
      const ClothResult r = simulate_cloth(model, L.body, L.body_frames, L.attached, co, [&](const ClothFrame& f) {
        if (f.frame > 0 && (f.frame % 10 == 0 || f.frame == co.frames)) {
          note(fmt::format("[{:3d} %] frame {}/{}: {} {}, closest {:.3g} mm, {:.1f} s", 100 * f.frame / co.frames,
                           f.frame, co.frames, preview ? f.preview_iterations : f.newton_iterations,
                           preview ? "preview rounds" : "Newton iterations", f.min_distance_mm,
                           sim_timer.seconds()));
        }
      });
      const double sim_seconds = sim_timer.seconds();

      // Outputs.
      const Timer write_timer;
      fs::create_directories(fs::path(o->outdir) / "frames");
      auto out = [&](const std::string& name) { return (fs::path(o->outdir) / name).string(); };
      double stress_top = 0, sliding_top = 0;
      for (double v : r.max_stress_kpa) stress_top = std::max(stress_top, v);
      for (double v : r.max_sliding_mm) sliding_top = std::max(sliding_top, v);
      TriMesh g = L.garment, b = L.body;
      std::vector<AnimatedMesh> anim(2);
      anim[0].name = "garment";
      anim[0].colour = {70, 130, 200};
      anim[0].faces = L.garment.faces;
      anim[1].name = "body";
      anim[1].colour = {225, 190, 160};
      anim[1].faces = L.body.faces;
      std::vector<double> times;
      json frames = json::array(), fields = json::array();
      // Built-in limbs: the signed clearance of the free vertices to the true
      // capsules (the engine's distances are unsigned, to the mesh).
      std::vector<char> held(model.num_vertices(), 0);
      for (int v : model.pinned) held[v] = 1;
      auto true_clearance = [&](const ClothFrame& f) {
        double c = std::numeric_limits<double>::infinity();
        for (int v = 0; v < model.num_vertices(); ++v)
          if (!held[v]) c = std::min(c, L.true_distance(L.joint_angle_deg[f.frame], f.positions[v]));
        return c;
      };
      double min_clearance = std::numeric_limits<double>::infinity();
      for (const ClothFrame& f : r.frames) {
        g.vertices = f.positions;
        b.vertices = f.body;
        const std::string stem = fmt::format("frames/{:04d}", f.frame);
        write_mesh(out(stem + "_garment.obj"), g);
        write_mesh(out(stem + "_body.obj"), b);
        MeshWriteOptions w;
        w.face_colours = to_rgb(scalar_colours(f.stress_kpa, 0.0, stress_top));
        w.vertex_colours = to_rgb(scalar_colours(f.sliding_mm, 0.0, sliding_top));
        write_mesh(out(stem + "_garment.ply"), g, w);
        anim[0].frames.push_back(f.positions);
        anim[1].frames.push_back(f.body);
        times.push_back(f.time_s);
        double smax = 0, lmax = 0;
        for (double v : f.stress_kpa) smax = std::max(smax, v);
        for (double v : f.sliding_mm) lmax = std::max(lmax, v);
        json fj = {{"frame", f.frame},
                   {"time_s", f.time_s},
                   {"newton_iterations", f.newton_iterations},
                   {"quasi_newton_iterations", f.quasi_newton_iterations},
                   {"factorizations", f.factorizations},
                   {"converged", f.converged},
                   {"solves_at_iteration_limit", f.solves_at_iteration_limit},
                   {"steps", f.steps},
                   {"contacts", f.contacts},
                   {"touching", f.touching},
                   {"min_distance_mm", finite_or_null(f.min_distance_mm)},
                   {"max_residual_force_mn", f.max_force_mn},
                   {"energy_uj",
                    {{"elastic", f.elastic_energy_uj},
                     {"kinetic", f.kinetic_energy_uj},
                     {"gravity", f.gravity_energy_uj},
                     {"total", f.elastic_energy_uj + f.kinetic_energy_uj + f.gravity_energy_uj}}},
                   {"max_stress_kpa", smax},
                   {"max_sliding_mm", lmax},
                   {"seconds", preview ? preview_timings_json(f.seconds) : newton_timings_json(f.seconds)}};
        if (preview) {
          fj["preview_iterations"] = f.preview_iterations;
          fj["preview_last_move_mm"] = f.preview_last_move_mm;
        }
        if (!L.joint_angle_deg.empty()) {
          fj[L.angle_key] = L.joint_angle_deg[f.frame];
          const double c = true_clearance(f);
          fj[L.clearance_key] = c;
          min_clearance = std::min(min_clearance, c);
        }
        frames.push_back(fj);
        fields.push_back({{"frame", f.frame}, {"stress_kpa", rounded(f.stress_kpa)}, {"sliding_mm", rounded(f.sliding_mm)}});
      }
      write_animation_glb(out("animation.glb"), anim, times);
      {
        MeshWriteOptions w;
        g.vertices = r.frames.back().positions;
        w.face_colours = to_rgb(scalar_colours(r.max_stress_kpa, 0.0, stress_top));
        w.vertex_colours = to_rgb(scalar_colours(r.max_sliding_mm, 0.0, sliding_top));
        write_mesh(out("maxima.ply"), g, w);
      }
      {
        // A picture of the last frame: the garment coloured by its stress
        // then (viridis on [0, the maximum over time]), the body skin-coloured.
        std::vector<RenderMesh> scene(2);
        scene[0].mesh = L.garment;
        scene[0].mesh.vertices = r.frames.back().positions;
        for (const Rgb8& c : scalar_colours(r.frames.back().stress_kpa, 0.0, stress_top))
          scene[0].face_colours.push_back({c[0], c[1], c[2]});
        scene[1].mesh = L.body;
        scene[1].mesh.vertices = r.frames.back().body;
        scene[1].normals = vertex_normals(scene[1].mesh);
        scene[1].colour = {225, 190, 160};
        std::vector<Vec3> points = scene[0].mesh.vertices;
        points.insert(points.end(), scene[1].mesh.vertices.begin(), scene[1].mesh.vertices.end());
        RasterOptions ro;
        ro.width = 800;
        ro.height = 560;
        const Camera cam = frame_points(points, 800.0 / 560.0, false, Vec3(0.3, -1.0, 0.45), Vec3::UnitZ());
        write_png(out("last_frame.png"), rasterize(scene, cam, ro));
      }
      int unconverged = 0, at_limit = 0;
      for (const ClothFrame& f : r.frames) {
        unconverged += f.converged ? 0 : 1;
        at_limit += f.solves_at_iteration_limit > 0 ? 1 : 0;
      }
      json summary;
      summary["command"] = "cloth";
      summary["scene"] = cloth_scene_to_json(scene);
      summary["scene"]["source"] = scene.where;
      summary["setup"] = {{"garment_vertices", model.num_vertices()},
                          {"garment_triangles", model.num_elements()},
                          {"garment", L.garment_source},
                          {"body_vertices", L.body.num_vertices()},
                          {"body_triangles", L.body.num_faces()},
                          {"pinned", L.pinned.size()},
                          {"attached", L.attached.size()},
                          {"time_step_s", 1.0 / (co.frame_rate_hz * co.substeps)},
                          {"materials", [&] {
                             json m = json::array();
                             for (const KnitMaterial& k : model.materials) m.push_back(k.name);
                             return m;
                           }()}};
      if (L.dress) {
        summary["setup"]["dress"] = {{"clearance_mm", scene.dress_clearance_mm},
                                     {"moved", L.dress->moved},
                                     {"inside", L.dress->inside},
                                     {"deepest_mm", L.dress->deepest_mm},
                                     {"largest_move_mm", L.dress->largest_move_mm},
                                     {"passes", L.dress->passes}};
      }
      summary["result"] = {{"solver", solver_name},
                           {"converged", r.converged},
                           {"frames_not_converged", unconverged},
                           {"frames_at_iteration_limit", at_limit},
                           {"newton_iterations", r.newton_iterations},
                           {"quasi_newton_iterations", r.quasi_newton_iterations},
                           {"factorizations", r.factorizations},
                           {"steps", r.steps},
                           {"min_distance_mm", finite_or_null(r.min_distance_mm)},
                           {L.clearance_key.empty() ? "min_arm_clearance_mm" : L.clearance_key,
                            finite_or_null(min_clearance)},
                           {"preview_iterations", r.preview_iterations},
                           {"penetration", preview ? kPreviewPenetration :
                            "min_distance_mm is the smallest unsigned distance of a free vertex to the body mesh over "
                            "all frames (> 0 by the barrier and collision-free steps, which keep every vertex on the "
                            "side of the body it starts on); for the built-in arm (leg), min_arm_clearance_mm "
                            "(min_leg_clearance_mm) is the smallest signed distance of a free vertex to the true capsules (negative inside; the "
                            "mesh is inscribed, so down to minus its chord sag)"},
                           {"max_stress_kpa", stress_top},
                           {"max_sliding_mm", sliding_top},
                           {"stress_measure",
                            "largest principal Cauchy membrane stress of each triangle / thickness (kPa, 0 when "
                            "compressed)"},
                           {"sliding_measure",
                            "per vertex: distance on the body between its contact point and the point where it first "
                            "touched (mm; touching = within sliding_distance_mm)"}};
      summary["seconds"] = {{"simulation", sim_seconds},
                            {preview ? "preview" : "newton",
                             preview ? preview_timings_json(r.seconds) : newton_timings_json(r.seconds)},
                            {"measures", r.measure_seconds}};
      summary["outputs"] = {{"animation", "animation.glb (garment and body, morph targets, LINEAR)"},
                            {"sequence", "frames/NNNN_garment.obj, frames/NNNN_body.obj"},
                            {"colours", "frames/NNNN_garment.ply: face colour = stress, vertex colour = sliding "
                                        "(viridis on [0, the maximum over time])"},
                            {"maxima", "maxima.ply (last frame; colours = maxima over time)"},
                            {"picture", "last_frame.png (garment coloured by its stress at the last frame)"},
                            {"fields", "cloth.json: per-frame stress per triangle and sliding per vertex"}};
      json full = summary;
      full["frames"] = frames;
      full["fields"] = fields;
      full["max_stress_kpa_per_triangle"] = rounded(r.max_stress_kpa);
      full["max_sliding_mm_per_vertex"] = rounded(r.max_sliding_mm);
      summary["frames"] = frames;
      write_report_json(out("cloth.json"), full, false);
      write_report_json(out("material.json"), material_to_json(model.materials[0]), false);
      // The report page: the body as the "target" layer, the garment as the
      // "relaxed" layer, at the last frame; the page animates them from
      // animation.glb (report_data()).
      write_mesh(out("target.ply"), b);
      g.vertices = r.frames.back().positions;
      write_mesh(out("relaxed.ply"), g);
      summary["seconds"]["write"] = write_timer.seconds();
      summary["seconds"]["total"] = all.seconds();
      summary["report_page"] = "report.html plays the animation (animation.glb: body = target layer, garment = "
                               "relaxed layer), opening at the last frame";
      write_report_json(out("report.json"), summary, o->json);
      ReportHtmlOptions ro;
      ro.title = "cloth: " + scene.where;
      write_report_html(o->outdir, ro);
      note(fmt::format("{} frames, {} steps, {}, {} factorisations{}; closest "
                       "distance to the body {:.3g} mm; largest stress {:.3g} kPa, sliding {:.3g} mm; {:.2f} s -> {}",
                       co.frames, r.steps,
                       preview ? fmt::format("{} preview rounds (projective dynamics)", r.preview_iterations)
                                  : fmt::format("{} Newton iterations, {} L-BFGS", r.newton_iterations,
                                                r.quasi_newton_iterations),
                       r.factorizations,
                       !unconverged ? ""
                       : preview ? fmt::format(" ({} frames with a step whose rounds did not reach the tolerance)",
                                                  unconverged)
                                    : fmt::format(" ({} frames with an unconverged solve, {} at the iteration limit)",
                                                  unconverged, at_limit),
                       r.min_distance_mm, stress_top, sliding_top, all.seconds(), o->outdir));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
