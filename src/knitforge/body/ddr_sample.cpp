#include "knitforge/body/ddr_sample.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/body/body_measurements.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/ddr_geometry.h"
#include "knitforge/body/generated_body.h"
#include "knitforge/body/render_dual_depth.h"
#include "knitforge/body/skin_body.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vec3 random_colour(std::mt19937_64& rng, double lo, double hi) {
  return {uniform(rng, lo, hi), uniform(rng, lo, hi), uniform(rng, lo, hi)};
}

// Half-range (mm) of a shape parameter of our model, by its name.
double shape_half_range(const std::string& name) {
  try {
    const Measurement m = measurement_from_key(name);
    if (m == Measurement::Stature) return 120.0;
    if (m == Measurement::HeadGirth || m == Measurement::NeckGirth) return 20.0;
    return measurement_info(m).is_girth ? 70.0 : 50.0;
  } catch (const InvalidInput&) {
    return 1.0;  // not a measurement: an SMPL beta
  }
}

}  // namespace

const BodyModel& ddr_body_model() {
  static const BodyModel model = make_generated_body({.edge_length = 30.0, .remesh_iterations = 3});
  return model;
}

DepthCamera ddr_camera(int size) {
  if (size < 16 || size > 1024) throw InvalidInput(fmt::format("DDR image size {} is outside 16..1024 pixels", size));
  DepthCamera c;
  c.width = c.height = size;
  const double f = 800.0 * size / 256.0, centre = 0.5 * (size - 1);
  c.K << f, 0, centre, 0, f, centre, 0, 0, 1;
  return c;
}

RigidTransform ddr_world_to_camera(const Vec3& centre, double azimuth_rad) {
  // The camera sits at centre + d (sin a, -cos a, 0) and looks at the centre.
  const Vec3 forward(-std::sin(azimuth_rad), std::cos(azimuth_rad), 0.0);
  const Vec3 up(0, 0, 1);
  const Vec3 right = forward.cross(up);
  const Vec3 down = forward.cross(right);
  RigidTransform t;
  t.rotation.row(0) = right.transpose();
  t.rotation.row(1) = down.transpose();
  t.rotation.row(2) = forward.transpose();
  const Vec3 eye = centre - kDdrCameraDistanceMm * forward;
  t.translation = -(t.rotation * eye);
  return t;
}

BodyParams random_ddr_body(const BodyModel& model, std::mt19937_64& rng) {
  BodyParams p = pose_preset(model, "t-pose");
  p.shape = Eigen::VectorXd::Zero(model.num_shapes());
  for (int k = 0; k < model.num_shapes(); ++k) {
    const double r = shape_half_range(model.shape_names[static_cast<size_t>(k)]);
    p.shape(k) = uniform(rng, -r, r);
  }
  const auto set = [&](const char* joint, const Vec3& w) {
    if (model.joint_index(joint) >= 0) set_joint_rotation(model, p, joint, w);
  };
  // Arms: lowered from the T by 15-80° (about ±y), swung forward/back a little (about z).
  const double left_down = uniform(rng, 15, 80) * kDeg, right_down = uniform(rng, 15, 80) * kDeg;
  set("left_shoulder", {0, left_down, uniform(rng, -20, 20) * kDeg});
  set("right_shoulder", {0, -right_down, uniform(rng, -20, 20) * kDeg});
  // Elbows bend forward (about the body's z in the T pose: the forearm swings to -y).
  set("left_elbow", {0, 0, -uniform(rng, 0, 70) * kDeg});
  set("right_elbow", {0, 0, uniform(rng, 0, 70) * kDeg});
  // Hips: flexion about x (forward leg: negative), a little abduction about y.
  set("left_hip", {uniform(rng, -25, 15) * kDeg, -uniform(rng, 0, 8) * kDeg, 0});
  set("right_hip", {uniform(rng, -25, 15) * kDeg, uniform(rng, 0, 8) * kDeg, 0});
  set("left_knee", {uniform(rng, 0, 35) * kDeg, 0, 0});
  set("right_knee", {uniform(rng, 0, 35) * kDeg, 0, 0});
  set("spine1", {uniform(rng, -5, 8) * kDeg, uniform(rng, -5, 5) * kDeg, uniform(rng, -10, 10) * kDeg});
  set("neck", {uniform(rng, -8, 8) * kDeg, uniform(rng, -5, 5) * kDeg, uniform(rng, -20, 20) * kDeg});
  return p;
}

std::vector<float> keypoint_heatmaps(const std::array<Vec2, kNumBodyKeypoints>& keypoints_px,
                                     const std::array<bool, kNumBodyKeypoints>& present, int size, double sigma_px) {
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  std::vector<float> maps(kNumBodyKeypoints * plane, 0.0f);
  const double inv = 1.0 / (2.0 * sigma_px * sigma_px);
  const int reach = static_cast<int>(std::ceil(4.0 * sigma_px));
  for (size_t k = 0; k < kNumBodyKeypoints; ++k) {
    if (!present[k] || !keypoints_px[k].allFinite()) continue;
    const Vec2 q = keypoints_px[k];
    // A keypoint whose Gaussian misses the image leaves its map empty (and
    // its coordinates may not fit an int).
    if (q.x() < -reach || q.y() < -reach || q.x() > size + reach || q.y() > size + reach) continue;
    const int u0 = std::max(0, static_cast<int>(std::floor(q.x())) - reach), u1 = std::min(size - 1, static_cast<int>(std::ceil(q.x())) + reach);
    const int v0 = std::max(0, static_cast<int>(std::floor(q.y())) - reach), v1 = std::min(size - 1, static_cast<int>(std::ceil(q.y())) + reach);
    for (int v = v0; v <= v1; ++v)
      for (int u = u0; u <= u1; ++u) {
        const double d2 = (u - q.x()) * (u - q.x()) + (v - q.y()) * (v - q.y());
        maps[k * plane + static_cast<size_t>(v * size + u)] = static_cast<float>(std::exp(-d2 * inv));
      }
  }
  return maps;
}

DdrSample render_ddr_sample(const BodyModel& model, const BodyKeypointRig& rig, const BodyParams& params,
                            double azimuth_rad, const DdrSceneOptions& options, uint64_t appearance_seed) {
  DdrSample s;
  s.size = options.size;
  s.camera = ddr_camera(options.size);
  const PosedBody posed = pose_body(model, params);
  s.body = posed_mesh(model, posed);
  s.world_to_camera = ddr_world_to_camera(bounding_box(s.body).center(), azimuth_rad);
  const auto world_keypoints = body_keypoints(rig, posed);
  std::array<bool, kNumBodyKeypoints> present{};
  for (size_t k = 0; k < world_keypoints.size(); ++k) {
    s.keypoints_mm[k] = s.world_to_camera.apply(world_keypoints[k]);
    const Vec3 p = s.camera.K * s.keypoints_mm[k];
    s.keypoints_px[k] = Vec2(p.x() / p.z(), p.y() / p.z());
    present[k] = true;
  }
  s.pelvis_mm = s.world_to_camera.apply(keypoint_pelvis(world_keypoints));
  s.heatmaps = keypoint_heatmaps(s.keypoints_px, present, options.size, ddr_heatmap_sigma(options));

  const DualDepthImage dd = render_dual_depth(s.body, s.camera, s.world_to_camera);
  const size_t plane = static_cast<size_t>(options.size) * static_cast<size_t>(options.size);
  s.ddr.assign(2 * plane, 0.0f);
  s.foreground.assign(plane, 0);
  s.rgb.assign(3 * plane, 0.0f);

  std::mt19937_64 rng(appearance_seed * 0x9E3779B97F4A7C15ull + 17);
  const Vec3 skin = Vec3(0.95, 0.75, 0.6).cwiseProduct(Vec3::Constant(uniform(rng, 0.45, 1.0)));
  const Vec3 top = random_colour(rng, 0.05, 0.95), bottom = random_colour(rng, 0.05, 0.8), shoes = random_colour(rng, 0.0, 0.4);
  const Vec3 sky = random_colour(rng, 0.2, 1.0), ground = random_colour(rng, 0.1, 0.8);
  // Towards the light, in the camera's frame: in front of the body (-z), above it (-y), to a side.
  const Vec3 light_camera = Vec3(uniform(rng, -0.7, 0.7), -uniform(rng, 0.1, 0.8), -1.0).normalized();
  const Vec3 light = s.world_to_camera.rotation.transpose() * light_camera;
  const double ambient = uniform(rng, 0.25, 0.45);
  const auto part_colour = [&](int face) -> Vec3 {
    if (model.vertex_parts.empty()) return top;
    switch (model.vertex_parts[static_cast<size_t>(model.faces[static_cast<size_t>(face)][0])]) {
      case BodyPart::Head:
      case BodyPart::Neck:
      case BodyPart::LeftHand:
      case BodyPart::RightHand: return skin;
      case BodyPart::LeftLeg:
      case BodyPart::RightLeg: return bottom;
      case BodyPart::LeftFoot:
      case BodyPart::RightFoot: return shoes;
      default: return top;
    }
  };
  for (size_t i = 0; i < plane; ++i) {
    const int v = static_cast<int>(i) / options.size;
    Vec3 colour;
    if (dd.min_face[i] >= 0) {
      s.foreground[i] = 1;
      s.ddr[i] = static_cast<float>((dd.min_mm[i] - s.pelvis_mm.z()) / kDdrDepthUnitMm);
      s.ddr[plane + i] = static_cast<float>((dd.max_mm[i] - s.pelvis_mm.z()) / kDdrDepthUnitMm);
      const auto& f = s.body.faces[static_cast<size_t>(dd.min_face[i])];
      const Vec3 n = (s.body.vertices[static_cast<size_t>(f[1])] - s.body.vertices[static_cast<size_t>(f[0])])
                         .cross(s.body.vertices[static_cast<size_t>(f[2])] - s.body.vertices[static_cast<size_t>(f[0])])
                         .normalized();
      colour = part_colour(dd.min_face[i]) * (ambient + (1.0 - ambient) * std::max(0.0, n.dot(light)));
    } else {
      const double t = static_cast<double>(v) / (options.size - 1);
      colour = t < 0.7 ? sky : ground;  // a wall and a floor
    }
    for (size_t c = 0; c < 3; ++c) s.rgb[c * plane + i] = static_cast<float>(std::clamp(colour(static_cast<int>(c)), 0.0, 1.0));
  }
  return s;
}

uint64_t ddr_train_seed(int i) { return static_cast<uint64_t>(i) + 1; }
uint64_t ddr_test_seed(int i) { return (uint64_t{1} << 40) + static_cast<uint64_t>(i); }

DdrSample synthetic_ddr_sample(const BodyModel& model, const BodyKeypointRig& rig, uint64_t seed,
                               const DdrSceneOptions& options) {
  std::mt19937_64 rng(seed * 0xD1B54A32D192ED03ull + 1);
  const BodyParams params = random_ddr_body(model, rng);
  const double azimuth = uniform(rng, -options.max_azimuth_deg, options.max_azimuth_deg) * kDeg;
  return render_ddr_sample(model, rig, params, azimuth, options, seed);
}

double ddr_heatmap_sigma(const DdrSceneOptions& options) {
  return options.heatmap_sigma_px > 0 ? options.heatmap_sigma_px : 1.5 * options.size / 64.0;
}

std::vector<float> ddr_view_input(const std::vector<Vec3>& points_mm,
                                  const std::array<Vec3, kNumBodyKeypoints>& keypoints_mm,
                                  const std::array<bool, kNumBodyKeypoints>& present, const Vec3& pelvis_mm,
                                  const DepthCamera& camera, double angle_rad, double sigma_px) {
  const int size = camera.width;
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  const RigidTransform turn = turn_about_vertical(pelvis_mm, angle_rad);
  const DepthImage depth = splat_min_depth(points_mm, camera, turn);
  std::vector<float> input((1 + kNumBodyKeypoints) * plane, 0.0f);
  for (size_t i = 0; i < plane; ++i)
    if (depth.depth_mm[i] > 0) input[i] = static_cast<float>((depth.depth_mm[i] - pelvis_mm.z()) / kDdrDepthUnitMm);
  std::array<Vec2, kNumBodyKeypoints> px;
  for (size_t k = 0; k < px.size(); ++k) {
    const Vec3 p = camera.K * turn.apply(keypoints_mm[k]);
    px[k] = Vec2(p.x() / p.z(), p.y() / p.z());
  }
  const std::vector<float> maps = keypoint_heatmaps(px, present, size, sigma_px);
  std::copy(maps.begin(), maps.end(), input.begin() + static_cast<std::ptrdiff_t>(plane));
  return input;
}

std::vector<float> ddr_view_truth(const DdrSample& sample, double angle_rad, std::vector<uint8_t>* foreground) {
  const RigidTransform view = turn_about_vertical(sample.pelvis_mm, angle_rad).after(sample.world_to_camera);
  const DualDepthImage dd = render_dual_depth(sample.body, sample.camera, view);
  const size_t plane = dd.min_mm.size();
  std::vector<float> truth(plane, 0.0f);
  if (foreground) foreground->assign(plane, 0);
  for (size_t i = 0; i < plane; ++i) {
    if (!dd.covered(static_cast<int>(i))) continue;
    truth[i] = static_cast<float>((dd.min_mm[i] - sample.pelvis_mm.z()) / kDdrDepthUnitMm);
    if (foreground) (*foreground)[i] = 1;
  }
  return truth;
}

std::vector<float> ddr_picture(const RgbImage& image, int size, double* scale) {
  if (image.width < size || image.height < size)
    throw InvalidInput(fmt::format("the picture is {} x {} pixels; the model needs at least {} x {}", image.width,
                                   image.height, size, size));
  if (std::abs(image.width - image.height) > 0.02 * std::max(image.width, image.height))
    throw InvalidInput(fmt::format("the picture is {} x {} pixels, not square: crop it to a square around the "
                                   "person (upright, whole, in the middle) first",
                                   image.width, image.height));
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  std::vector<float> out(3 * plane, 0.0f);
  const double sx = static_cast<double>(image.width) / size, sy = static_cast<double>(image.height) / size;
  for (int v = 0; v < size; ++v)
    for (int u = 0; u < size; ++u) {
      // The source pixels whose centres fall in this pixel's box.
      const int x0 = static_cast<int>(std::floor(u * sx)), x1 = std::max(x0 + 1, static_cast<int>(std::floor((u + 1) * sx)));
      const int y0 = static_cast<int>(std::floor(v * sy)), y1 = std::max(y0 + 1, static_cast<int>(std::floor((v + 1) * sy)));
      std::array<double, 3> sum{};
      int count = 0;
      for (int y = y0; y < std::min(y1, image.height); ++y)
        for (int x = x0; x < std::min(x1, image.width); ++x) {
          const RenderColour c = image.at(x, y);
          for (size_t k = 0; k < 3; ++k) sum[k] += c[k];
          ++count;
        }
      for (size_t c = 0; c < 3; ++c)
        out[c * plane + static_cast<size_t>(v * size + u)] = static_cast<float>(sum[c] / (255.0 * std::max(count, 1)));
    }
  if (scale) *scale = 1.0 / sx;
  return out;
}

RgbImage ddr_picture_image(const DdrSample& sample) {
  const size_t plane = static_cast<size_t>(sample.size) * static_cast<size_t>(sample.size);
  RgbImage image{sample.size, sample.size, std::vector<uint8_t>(3 * plane)};
  for (size_t i = 0; i < plane; ++i)
    for (size_t c = 0; c < 3; ++c)
      image.pixels[3 * i + c] = static_cast<uint8_t>(std::lround(255.0 * sample.rgb[c * plane + i]));
  return image;
}

RgbImage ddr_depth_picture(const std::vector<float>& ddr, int size) {
  const size_t plane = static_cast<size_t>(size) * static_cast<size_t>(size);
  if (ddr.size() != 2 * plane)
    throw InvalidInput(fmt::format("a {0} x {0} DDR has {1} values, not {2}", size, ddr.size(), 2 * plane));
  RgbImage image{2 * size, size, std::vector<uint8_t>(3 * 2 * plane, 0)};
  for (int c = 0; c < 2; ++c)
    for (int v = 0; v < size; ++v)
      for (int u = 0; u < size; ++u) {
        const double d = ddr[static_cast<size_t>(c) * plane + static_cast<size_t>(v * size + u)];
        if (std::abs(d) <= kDdrForegroundThreshold) continue;
        const auto grey = static_cast<uint8_t>(std::clamp(128.0 - d * kDdrDepthUnitMm / 4.0, 1.0, 255.0));
        const size_t at = 3 * (static_cast<size_t>(v) * 2 * static_cast<size_t>(size) + static_cast<size_t>(c * size + u));
        image.pixels[at] = image.pixels[at + 1] = image.pixels[at + 2] = grey;
      }
  return image;
}

}  // namespace knitforge
