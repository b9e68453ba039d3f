// knitforge body render-photo: a synthetic picture of a body with its
// OpenPose keypoints, as the single-image reconstruction (seed §5.4) is
// trained and tested on, for trying `knitforge body reconstruct`.
#include <memory>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/ddr_sample.h"
#include "knitforge/body/openpose_json.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/png_image.h"
#include "knitforge/util/atomic_file.h"

namespace knitforge::cli {

namespace {

struct PhotoOptions {
  std::string output;
  std::string keypoints;
  std::string truth;
  std::string ddr;
  int size = 256;
  int test = -1;
  uint64_t seed = 1;
  double max_azimuth = 90;
};

int run_photo(const PhotoOptions& o) {
  check_output_file("-o", o.output, {".png"});
  check_output_file("--keypoints", o.keypoints, {".json"});
  if (!o.truth.empty()) check_output_file("--truth", o.truth, {".obj", ".ply", ".off", ".stl"});
  if (!o.ddr.empty()) check_output_file("--ddr", o.ddr, {".png"});
  const BodyModel& model = ddr_body_model();
  const uint64_t seed = o.test >= 0 ? ddr_test_seed(o.test) : o.seed;
  const DdrSample s = synthetic_ddr_sample(model, body_keypoint_rig(model), seed, {o.size, o.max_azimuth, 0.0});
  PersonKeypoints person;
  person.px = s.keypoints_px;
  person.present.fill(true);
  write_png(o.output, ddr_picture_image(s));
  const std::string json = openpose_keypoints_to_json(person).dump(1);
  write_file_atomically(o.keypoints, [&](std::ostream& out) { out << json << "\n"; });
  if (!o.ddr.empty()) write_png(o.ddr, ddr_depth_picture(s.ddr, s.size));
  if (!o.truth.empty()) {
    TriMesh truth = s.body;
    const RigidTransform to_body = camera_to_body_frame(s.pelvis_mm).after(s.world_to_camera);
    for (Vec3& x : truth.vertices) x = to_body.apply(x);
    write_mesh(o.truth, truth);
  }
  note(fmt::format("body render-photo: {} x {} picture of synthetic body {}seed {}; keypoints in {}", o.size, o.size,
                   o.test >= 0 ? fmt::format("test {}, ", o.test) : "", seed, o.keypoints));
  return 0;
}

}  // namespace

void add_body_photo_command(CLI::App& body, Action& action) {
  auto* photo = body.add_subcommand(
      "render-photo", "A synthetic picture of a random body of our model with its OpenPose keypoints (and the true "
                      "body): what body reconstruct is trained and tested on");
  auto o = std::make_shared<PhotoOptions>();
  photo->add_option("-o,--output", o->output, "The picture (PNG)")->required();
  photo->add_option("--keypoints", o->keypoints, "Its keypoints (OpenPose COCO-18 JSON)")->required();
  photo->add_option("--truth", o->truth,
                    "Also the true body mesh, in the frame body reconstruct writes (origin at the pelvis, x right, y "
                    "away from the camera, z up; mm)");
  photo->add_option("--ddr", o->ddr, "Also the true DDR as a picture (PNG: I_min | I_max)");
  photo->add_option("--size", o->size, "Picture side in pixels (default 256)")->check(CLI::Range(16, 1024));
  auto* test = photo->add_option("--test", o->test,
                                 "The N-th held-out body of ddr-train's evaluation (never trained on)")
                   ->check(CLI::Range(0, 1000000));
  photo->add_option("--seed", o->seed, "Seed of a random body (default 1; training uses seeds 1..samples)")->excludes(test);
  photo->add_option("--max-azimuth", o->max_azimuth, "Views within ±this many degrees of the front (default 90)")
      ->check(number_in(0.0, 180.0));
  photo->callback([o, &action] { action = [o] { return run_photo(*o); }; });
}

}  // namespace knitforge::cli
