// The cloth scene reader (docs/formats.md, "Cloth scene"): defaults,
// relative paths, and every bad input refused with a message naming it.
#include "knitforge/sim/cloth_scene.h"

#include <gtest/gtest.h>

#include <string>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

using nlohmann::json;

// The message of the InvalidInput that reading j throws ("" when none).
std::string refusal(const json& j) {
  try {
    (void)cloth_scene_from_json(j, "scene.json", "/data");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

json file_scene() {
  return json::parse(R"({"garment": {"mesh": "sleeve.obj", "course_axis": {"point": [0, 0, 0], "direction": [1, 0, 0]}},
                         "body": {"frames": ["a.obj", "b.obj", "c.obj"]}, "frames": 2, "frame_rate_hz": 24,
                         "substeps": 3, "friction": 0.2, "attach": [0, 5]})");
}

TEST(ClothScene, ReadsAFileSceneWithPathsRelativeToIt) {
  const ClothScene s = cloth_scene_from_json(file_scene(), "scene.json", "/data");
  EXPECT_EQ(s.garment_mesh, "/data/sleeve.obj");
  ASSERT_EQ(s.body_frames.size(), 3u);
  EXPECT_EQ(s.body_frames[2], "/data/c.obj");
  EXPECT_EQ(s.frames, 2);
  EXPECT_DOUBLE_EQ(s.frame_rate_hz, 24.0);
  EXPECT_EQ(s.substeps, 3);
  EXPECT_DOUBLE_EQ(s.friction, 0.2);
  EXPECT_EQ(s.attached, (std::vector<int>{0, 5}));
  ASSERT_TRUE(s.course_axis.has_value());
  EXPECT_FALSE(s.course_direction.has_value());
  EXPECT_EQ(s.materials.size(), 1u);
  EXPECT_DOUBLE_EQ(s.gravity_mm_s2.z(), -9810.0);
  // Round trip through the recorded form.
  const ClothScene t = cloth_scene_from_json(cloth_scene_to_json(s), "again");
  EXPECT_EQ(t.body_frames, s.body_frames);
  EXPECT_EQ(t.attached, s.attached);
}

TEST(ClothScene, ReadsAGltfBodyAnimation) {
  json j = file_scene();
  j["body"] = json::parse(R"({"animation": "walk.glb", "mesh_name": "body", "animation_name": "walk", "units": "m"})");
  j.erase("frames");
  const ClothScene s = cloth_scene_from_json(j, "scene.json", "/data");
  EXPECT_EQ(s.body_animation, "/data/walk.glb");
  EXPECT_EQ(s.body_mesh_name, "body");
  EXPECT_EQ(s.body_animation_name, "walk");
  EXPECT_EQ(s.body_units, "m");
  EXPECT_FALSE(s.frames_given);  // the CLI takes the animation's length
  const ClothScene t = cloth_scene_from_json(cloth_scene_to_json(s), "again");
  EXPECT_EQ(t.body_animation, s.body_animation);
  EXPECT_EQ(t.body_mesh_name, "body");
  EXPECT_EQ(t.body_animation_name, "walk");
  EXPECT_TRUE(t.frames_given);
  j["body"]["mesh"] = "x.obj";
  EXPECT_NE(refusal(j).find("exactly one of \"mesh\""), std::string::npos);
  j["body"] = json::parse(R"({"mesh": "x.obj", "mesh_name": "body"})");
  EXPECT_NE(refusal(j).find("'body.mesh_name' goes with \"animation\""), std::string::npos);
}

TEST(ClothScene, AStitchMeshGarmentBringsItsOwnCourses) {
  json j = file_scene();
  j["garment"] = json::parse(R"({"design": "out/cup", "stitch_size": "4x3"})");
  const ClothScene s = cloth_scene_from_json(j, "scene.json", "/data");
  EXPECT_EQ(s.garment_design, "/data/out/cup");
  EXPECT_EQ(s.garment_stitch_size, "4x3");
  EXPECT_TRUE(s.garment_mesh.empty());
  const ClothScene t = cloth_scene_from_json(cloth_scene_to_json(s), "again");
  EXPECT_EQ(t.garment_design, s.garment_design);
  EXPECT_EQ(t.garment_stitch_size, "4x3");
  j["garment"] = json::parse(R"({"stitch_mesh": "cup.ply", "mesh": "cup.obj"})");
  EXPECT_NE(refusal(j).find("exactly one of \"mesh\""), std::string::npos);
  j["garment"] = json::parse(R"({"stitch_mesh": "cup.ply", "course_axis": {"point": [0, 0, 0], "direction": [1, 0, 0]}})");
  EXPECT_NE(refusal(j).find("'garment.course_axis' is for a triangle-mesh garment"), std::string::npos);
  j["garment"] = json::parse(R"({"stitch_mesh": "cup.ply", "face_materials": [0]})");
  EXPECT_NE(refusal(j).find("'garment.face_materials' is for a triangle-mesh garment"), std::string::npos);
  j["garment"] = json::parse(R"({"stitch_mesh": "cup.ply", "units": "cm"})");
  EXPECT_NE(refusal(j).find("'garment.units' must be mm for a stitch mesh"), std::string::npos);
  j["garment"] = json::parse(R"({"mesh": "cup.obj", "course_direction": [1, 0, 0], "stitch_size": "4x3"})");
  EXPECT_NE(refusal(j).find("'garment.stitch_size' goes with"), std::string::npos);
}

TEST(ClothScene, BuiltinNeedsNoFile) {
  const ClothScene s = builtin_cloth_scene("sleeve");
  EXPECT_EQ(s.builtin, "sleeve");
  EXPECT_TRUE(s.garment_mesh.empty());
  const ClothScene t = cloth_scene_from_json(json::parse(R"({"builtin": "sleeve", "arm": {"max_angle_deg": 45}, "frames": 4})"),
                                             "scene.json");
  EXPECT_DOUBLE_EQ(t.arm.max_angle_deg, 45.0);
  EXPECT_EQ(t.frames, 4);
}

TEST(ClothScene, ASceneMayAskForThePreview) {
  EXPECT_FALSE(builtin_cloth_scene("sleeve").preview);
  const ClothScene s = cloth_scene_from_json(
      json::parse(R"({"builtin": "sleeve", "solver": "preview", "preview": {"max_iterations": 12}})"), "scene.json");
  EXPECT_TRUE(s.preview);
  EXPECT_EQ(s.preview_iterations, 12);
  const json back = cloth_scene_to_json(s);
  EXPECT_EQ(back["solver"], "preview");
  EXPECT_EQ(back["preview"]["max_iterations"], 12);
  EXPECT_FALSE(cloth_scene_from_json(json::parse(R"({"builtin": "sleeve", "solver": "implicit"})"), "s").preview);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "sleeve", "solver": "explicit"})"))
                .find("'solver' must be \"implicit\" (the default) or \"preview\""),
            std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "sleeve", "preview": {"rounds": 3}})")).find("unknown field 'preview.rounds'"),
            std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "sleeve", "preview": {"max_iterations": 0}})"))
                .find("'preview.max_iterations' must be in [1, 100000]"),
            std::string::npos);
}

TEST(ClothScene, RefusesBadInputsNamingTheField) {
  auto with = [](const std::string& key, const json& value) {
    json j = file_scene();
    j[key] = value;
    return j;
  };
  EXPECT_NE(refusal(with("frame", 3)).find("unknown field 'frame'"), std::string::npos);
  EXPECT_NE(refusal(with("frames", 0)).find("'frames' must be in [1, 100000]"), std::string::npos);
  EXPECT_NE(refusal(with("frames", 2.5)).find("'frames' must be an integer"), std::string::npos);
  EXPECT_NE(refusal(with("frame_rate_hz", -1)).find("'frame_rate_hz' must be positive"), std::string::npos);
  EXPECT_NE(refusal(with("friction", -0.1)).find("'friction' must be >= 0"), std::string::npos);
  EXPECT_NE(refusal(with("gravity_mm_s2", json::array({0, 0}))).find("'gravity_mm_s2' must be [x, y, z]"),
            std::string::npos);
  EXPECT_NE(refusal(with("attach", json::array({1, -2}))).find("'attach[1]'"), std::string::npos);
  // frames + 1 body meshes.
  EXPECT_NE(refusal(with("frames", 5)).find("has 3 meshes; a run of 5 frames needs frames + 1 = 6"),
            std::string::npos);
  json j = file_scene();
  j["garment"].erase("course_axis");
  EXPECT_NE(refusal(j).find("exactly one of \"course_direction\" and \"course_axis\""), std::string::npos);
  j = file_scene();
  j["garment"]["course_direction"] = json::array({0, 0, 1});
  EXPECT_NE(refusal(j).find("exactly one of"), std::string::npos);
  j = file_scene();
  j["garment"].erase("course_axis");
  j["garment"]["course_direction"] = json::array({0, 0, 0});
  EXPECT_NE(refusal(j).find("'garment.course_direction' must be a non-zero direction"), std::string::npos);
  j = file_scene();
  j["garment"]["units"] = "inch";
  EXPECT_NE(refusal(j).find("'garment.units' must be mm, cm or m"), std::string::npos);
  j = file_scene();
  j["garment"]["face_materials"] = json::array({0, 1});
  EXPECT_NE(refusal(j).find("'garment.face_materials[1]' is material 1, but there are 1 materials"), std::string::npos);
  j = file_scene();
  j["garment"]["material"] = json::parse(R"({"thickness_mm": -1})");
  EXPECT_NE(refusal(j).find("garment.material"), std::string::npos);
  j = file_scene();
  j["body"]["mesh"] = "x.obj";
  EXPECT_NE(refusal(j).find("exactly one of \"mesh\""), std::string::npos);
  j = file_scene();
  j.erase("body");
  EXPECT_NE(refusal(j).find("'body' is missing"), std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "skirt"})")).find("'skirt' is not a built-in scene (known: sleeve, legging)"),
            std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "sleeve", "garment": {}})")).find("brings its own garment"),
            std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "sleeve", "arm": {"elbow": 1}})")).find("unknown field 'arm.elbow'"),
            std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"builtin": "sleeve", "arm": {"forearm_radius_mm": 60}})"))
                .find("forearm radius 60 mm exceeds the upper arm's 45 mm"),
            std::string::npos);
  EXPECT_NE(refusal(json::parse(R"({"arm": {}})")).find("is a parameter of the built-in sleeve"), std::string::npos);
  EXPECT_NE(refusal(json::array()).find("must be a JSON object"), std::string::npos);
}

TEST(ClothScene, FileErrorsAreIOErrors) {
  EXPECT_THROW((void)read_cloth_scene("/nonexistent/scene.json"), IOError);
}

}  // namespace
}  // namespace knitforge
