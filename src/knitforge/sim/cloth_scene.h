#pragma once
/// \file cloth_scene.h
/// The scene of `knitforge cloth` (docs/formats.md, "Cloth scene"): a
/// garment, a body that moves, and how to simulate them, read from JSON with
/// every field named with its unit. Unknown fields are an error (a typo
/// would silently keep a default). The reader checks the scene's own
/// values; the meshes it names are read by the caller (the CLI, with the
/// readers of io/) and checked against the scene there (counts, indices).
///
///   {"garment": {"mesh": "sleeve.obj", "units": "mm",      // or
///                "stitch_mesh": "relaxed.ply" | "design": "out/dir",
///                "stitch_size": "3.5x2.8",  (stitch meshes: no course)
///                "course_direction": [0, 0, 1]            // or
///                "course_axis": {"point": [0,0,0], "direction": [1,0,0]},
///                "material": "jersey.json" | {...},       // or
///                "materials": [...], "face_materials": [0, 1, ...],
///                "clearance_mm": 1},  (dress the body: dress_garment.h)
///    "body": {"mesh": "arm.obj"}                          // static, or
///    "body": {"frames": ["arm_000.obj", ...], "units": "mm"},  // or
///    "body": {"animation": "walk.glb", "mesh_name": "body",   // glTF
///             "animation_name": "walk", "units": "mm"},
///    "frames": 30, "frame_rate_hz": 30, "substeps": 2,
///    "friction": 0.5, "gravity_mm_s2": [0, 0, -9810],
///    "pin": [vertex, ...], "attach": [vertex, ...], "attach_within_mm": 0,
///    "contact_distance_mm": 0.5, "sliding_distance_mm": 1.0,
///    "newton": {"max_iterations": 20, "force_tolerance_mn": 0.01},
///    "solver": "implicit" | "preview", "preview": {"max_iterations": 30}}
///
/// or a built-in scene: {"builtin": "sleeve", "arm": {ArmMotionParams
/// fields}, ...run fields} (arm_motion.h) or {"builtin": "legging", "leg":
/// {LegMotionParams fields}, ...} (leg_motion.h), which need no file.
/// Paths are relative to the scene file's directory.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knitforge/geometry/vec.h"
#include "knitforge/sim/arm_motion.h"
#include "knitforge/sim/knit_material.h"
#include "knitforge/sim/leg_motion.h"

namespace knitforge {

/// The built-in scene names ("sleeve", "legging").
const std::vector<std::string>& builtin_cloth_scene_names();

struct ClothScene {
  std::string where;    ///< the scene file, or "built-in NAME"
  std::string builtin;  ///< "" or a name of builtin_cloth_scene_names()
  ArmMotionParams arm;  ///< the built-in sleeve's arm
  LegMotionParams leg;  ///< the built-in legging's leg

  // The garment (file scenes): a triangle mesh with a course direction, or
  // a stitch mesh (a PLY or map of `relax`, or a design directory's
  // stitch_mesh.ply) whose stitches give the courses and rest shape.
  std::string garment_mesh;    ///< path (resolved)
  std::string garment_stitch_mesh;  ///< path (resolved): a stitch mesh PLY or a knitting map
  std::string garment_design;       ///< path (resolved): a design command's output directory
  std::string garment_stitch_size;  ///< "WxH" mm; "" = the design's report.json, else 3.5x2.8
  std::string garment_units = "mm";  ///< mm, cm or m (the caller scales)
  std::optional<Vec3> course_direction;
  /// Courses round an axis (a tube): course = direction x (centroid - point).
  std::optional<std::pair<Vec3, Vec3>> course_axis;
  std::vector<KnitMaterial> materials{default_single_jersey()};
  std::vector<int> face_materials;  ///< empty (all materials[0]) or one per face
  /// > 0: the garment's start is moved out of the body to this clearance
  /// (dress_garment(); a garment designed on the body's surface); 0: as given.
  double dress_clearance_mm = 0.0;

  // The body (file scenes): one static mesh, frames + 1 meshes, or a glTF
  // animation (io/read_gltf_animation.h) sampled at the frame times from
  // its first key on; without "frames" the run lasts the animation.
  std::string body_mesh;
  std::vector<std::string> body_frames;
  std::string body_animation;       ///< .glb / .gltf path (resolved)
  std::string body_mesh_name;       ///< "" = every mesh node; else a node or mesh name
  std::string body_animation_name;  ///< "" = the file's only animation
  std::string body_units = "mm";

  // Pins: held in place (world), attached (carried with the closest body
  // point, in its face's frame), every vertex within attach_within_mm of
  // the body at the start attached.
  std::vector<int> pinned, attached;
  double attach_within_mm = 0.0;

  // The run.
  int frames = 30;
  bool frames_given = false;  ///< "frames" was in the scene (else a glTF body sets it)
  double frame_rate_hz = 30.0;
  int substeps = 2;
  double friction = 0.5;
  Vec3 gravity_mm_s2{0.0, 0.0, -9810.0};
  double contact_distance_mm = 0.5;
  double sliding_distance_mm = 1.0;
  int max_newton_iterations = 20;
  double force_tolerance_mn = 1e-2;
  /// "solver": "preview" runs the fast preview (projective dynamics,
  /// simulate_cloth.h ClothSolver::Preview) instead of the implicit solver.
  bool preview = false;
  int preview_iterations = 30;  ///< "preview": {"max_iterations": N}, its rounds a step at most
};

/// The scene of a JSON value; `where` names it in messages, relative paths
/// are resolved against `base_dir` ("" = as given).
/// \throw InvalidInput naming `where` and the field for an unknown field, a
///        wrong type, a value out of range (frames 1..100000, frame rate
///        and substeps positive, friction >= 0, ...), a garment without a
///        course direction, a body without exactly one of mesh, frames and
///        animation, a frame list whose length is not frames + 1, a vertex index < 0, an unknown built-in name.
ClothScene cloth_scene_from_json(const nlohmann::json& j, const std::string& where, const std::string& base_dir = "");

/// Reads a scene file. \throw IOError when it cannot be read or is not
///        JSON (naming the parser's position); InvalidInput as above.
ClothScene read_cloth_scene(const std::string& path);

/// The built-in scene `name` with its defaults (= cloth_scene_from_json({"builtin": name})).
ClothScene builtin_cloth_scene(const std::string& name);

/// The scene as JSON (what cloth.json records; paths as resolved).
nlohmann::json cloth_scene_to_json(const ClothScene& scene);

}  // namespace knitforge
