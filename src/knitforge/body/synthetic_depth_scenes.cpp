#include "knitforge/body/synthetic_depth_scenes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <fmt/core.h>

#include "knitforge/body/json_values.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kRad = std::numbers::pi / 180.0;

Mat3 rot(const Vec3& axis, double deg) { return Eigen::AngleAxisd(deg * kRad, axis.normalized()).toRotationMatrix(); }

// World-to-camera motion of a camera at `centre` with rotation R (rows: the
// camera's x, y, z axes in the world).
RigidTransform placed(const Mat3& R, const Vec3& centre) { return {R, -(R * centre)}; }

}  // namespace

DepthRig seed_depth_rig(double distance_mm, double height_mm) {
  DepthCamera cam;
  cam.width = 480;
  cam.height = 640;
  cam.K << 280.0, 0.0, 239.5, 0.0, 280.0, 319.5, 0.0, 0.0, 1.0;
  cam.depth_unit_mm = 1.0;
  DepthRig rig;
  rig.camera1 = rig.camera2 = cam;
  Mat3 R1, R2;
  // Camera 1 looks along +y: x_c = x, y_c = -z (image down), z_c = y.
  R1 << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  // Camera 2 looks along -y: x_c = -x, y_c = -z, z_c = -y.
  R2 << -1, 0, 0, 0, 0, -1, 0, -1, 0;
  // Set up by hand: yaw about the camera's y, pitch about its x, roll about its z.
  R2 = rot(Vec3::UnitZ(), 1.5) * rot(Vec3::UnitX(), -4.0) * rot(Vec3::UnitY(), 3.0) * R2;
  rig.world_to_camera1 = placed(R1, Vec3(0.0, -0.5 * distance_mm, height_mm));
  rig.world_to_camera2 = placed(R2, Vec3(60.0, 0.5 * distance_mm, height_mm + 40.0));
  return rig;
}

RigidTransform camera2_to_camera1(const DepthRig& rig) {
  const RigidTransform& a = rig.world_to_camera1;
  const RigidTransform& b = rig.world_to_camera2;
  const RigidTransform b_inv{b.rotation.transpose(), -(b.rotation.transpose() * b.translation)};
  return a.after(b_inv);
}

nlohmann::json rigid_transform_to_json(const RigidTransform& T) {
  return {{"R", json_values::to_json(T.rotation)}, {"t", json_values::to_json(T.translation)}};
}

RigidTransform rigid_transform_from_json(const nlohmann::json& json, const std::string& what) {
  return {json_values::rotation(json_values::field(json, "R", what), what + ": R"),
          json_values::vec3(json_values::field(json, "t", what), what + ": t")};
}

nlohmann::json depth_rig_to_json(const DepthRig& rig) {
  return {{"camera1", depth_camera_to_json(rig.camera1)},
          {"camera2", depth_camera_to_json(rig.camera2)},
          {"world_to_camera1", rigid_transform_to_json(rig.world_to_camera1)},
          {"world_to_camera2", rigid_transform_to_json(rig.world_to_camera2)},
          {"camera2_to_camera1", rigid_transform_to_json(camera2_to_camera1(rig))}};
}

DepthRig depth_rig_from_json(const nlohmann::json& json, const std::string& what) {
  DepthRig rig;
  rig.camera1 = depth_camera_from_json(json_values::field(json, "camera1", what), what + ": camera1");
  rig.camera2 = depth_camera_from_json(json_values::field(json, "camera2", what), what + ": camera2");
  rig.world_to_camera1 =
      rigid_transform_from_json(json_values::field(json, "world_to_camera1", what), what + ": world_to_camera1");
  rig.world_to_camera2 =
      rigid_transform_from_json(json_values::field(json, "world_to_camera2", what), what + ": world_to_camera2");
  return rig;
}

TriMesh board_mesh(const BoardSize& size, const RigidTransform& pose) {
  if (!(size.width_mm > 0.0) || !(size.height_mm > 0.0) || !(size.thickness_mm > 0.0) ||
      !std::isfinite(size.width_mm + size.height_mm + size.thickness_mm))
    throw InvalidInput(fmt::format("board {}x{}x{} mm: every size must be a positive number", size.width_mm,
                                   size.height_mm, size.thickness_mm));
  TriMesh m;
  const Vec3 half(0.5 * size.width_mm, 0.5 * size.thickness_mm, 0.5 * size.height_mm);
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back(pose.apply(Vec3((i & 1 ? 1 : -1) * half.x(), (i & 2 ? 1 : -1) * half.y(),
                                         (i & 4 ? 1 : -1) * half.z())));
  // Outward, counter-clockwise: two triangles per side of the box.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

std::vector<RigidTransform> random_board_poses(const DepthRig& rig, int k, unsigned seed) {
  if (k < 1 || k > 100) throw InvalidInput(fmt::format("random_board_poses: {} poses; give 1 to 100", k));
  const auto centre_of = [](const RigidTransform& T) { return Vec3(-(T.rotation.transpose() * T.translation)); };
  const Vec3 mid = 0.5 * (centre_of(rig.world_to_camera1) + centre_of(rig.world_to_camera2));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * u01(rng); };
  std::vector<RigidTransform> poses;
  std::vector<Vec3> normals;
  const double phi0 = uniform(0.0, 360.0);
  for (int attempt = 0; static_cast<int>(poses.size()) < k; ++attempt) {
    if (attempt > 1000 * k) throw InvalidInput(fmt::format("random_board_poses: cannot place {} poses 10° apart", k));
    // The tilt axes go round the circle (360/k apart, jittered), so the
    // normals spread over 3D as a careful operator's would.
    const double phi = phi0 + 360.0 * static_cast<double>(poses.size()) / k + uniform(-20.0, 20.0);
    const double tilt = uniform(15.0, 40.0), turn = uniform(-30.0, 30.0);
    const Vec3 axis(std::cos(phi * kRad), 0.0, std::sin(phi * kRad));
    const Mat3 R = rot(axis, tilt) * rot(Vec3::UnitY(), turn);
    const Vec3 n = R * Vec3::UnitY();
    bool apart = true;
    for (const Vec3& m : normals) apart = apart && std::acos(std::clamp(n.dot(m), -1.0, 1.0)) > 10.0 * kRad;
    const Vec3 c = mid + Vec3(uniform(-150.0, 150.0), uniform(-100.0, 100.0), uniform(-150.0, 150.0));
    if (!apart) continue;
    normals.push_back(n);
    poses.push_back({R, c});
  }
  return poses;
}

void add_depth_noise(DepthImage& image, const DepthNoise& noise) {
  if (!(noise.sigma_mm >= 0.0) || !(noise.outlier_fraction >= 0.0 && noise.outlier_fraction <= 1.0))
    throw InvalidInput(fmt::format("depth noise: sigma {} mm must be >= 0 and the outlier fraction {} in [0, 1]",
                                   noise.sigma_mm, noise.outlier_fraction));
  std::mt19937 rng(noise.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (double& z : image.depth_mm) {
    const double g = gauss(rng), o = u01(rng), far = u01(rng);  // drawn for every pixel: stable streams
    if (o < noise.outlier_fraction) {
      z = 300.0 + 3700.0 * far;
    } else if (z > 0.0) {
      z = std::max(1.0, z + noise.sigma_mm * g);
    }
  }
}

}  // namespace knitforge
