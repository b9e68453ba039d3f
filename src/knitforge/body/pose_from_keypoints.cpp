#include "knitforge/body/pose_from_keypoints.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/core.h>

#include "knitforge/body/axis_angle.h"
#include "knitforge/body/body_measurements.h"
#include "knitforge/body/shape_body.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

struct Kinematics {
  std::vector<Vec3> o;  // posed joints
  std::vector<Mat3> Q;  // global rotations
};

Kinematics forward(const BodyModel& m, const std::vector<Vec3>& rest, const std::vector<Mat3>& R, const Vec3& t) {
  const int J = m.num_joints();
  Kinematics k;
  k.o.resize(static_cast<size_t>(J));
  k.Q.resize(static_cast<size_t>(J));
  for (int j = 0; j < J; ++j) {
    const auto sj = static_cast<size_t>(j);
    const int p = m.parents[sj];
    if (p < 0) {
      k.Q[sj] = R[sj];
      k.o[sj] = rest[sj] + t;
    } else {
      const auto sp = static_cast<size_t>(p);
      k.Q[sj] = k.Q[sp] * R[sj];
      k.o[sj] = k.o[sp] + k.Q[sp] * (rest[sj] - rest[sp]);
    }
  }
  return k;
}

// The smallest rotation turning unit vector a onto unit vector b.
Mat3 swing(const Vec3& a, const Vec3& b) {
  const Vec3 axis = a.cross(b);
  const double s = axis.norm(), c = std::clamp(a.dot(b), -1.0, 1.0);
  if (s < 1e-12) {
    if (c > 0.0) return Mat3::Identity();
    // Opposite: half a turn about any axis normal to a.
    Vec3 n = a.cross(Vec3::UnitX());
    if (n.norm() < 1e-6) n = a.cross(Vec3::UnitY());
    return rotation_from_axis_angle(std::acos(-1.0) * n.normalized());
  }
  return rotation_from_axis_angle(std::atan2(s, c) * axis / s);
}

}  // namespace

KeypointPose pose_from_keypoints(const BodyModel& model, const std::map<std::string, Vec3>& keypoints_mm,
                                 const BodyParams& start) {
  validate_body_params(model, start);
  const int J = model.num_joints();
  std::vector<std::optional<Vec3>> obs(static_cast<size_t>(J));
  KeypointPose out;
  for (const auto& [name, p] : keypoints_mm) {
    const int j = model.joint_index(name);
    if (j < 0) {
      std::string names;
      for (const auto& n : model.joint_names) names += (names.empty() ? "" : ", ") + n;
      throw InvalidInput(fmt::format("keypoint '{}' is no joint of the body model '{}'; the joints: {}", name,
                                     model.name, names));
    }
    if (!p.allFinite()) throw InvalidInput(fmt::format("keypoint '{}' is not finite", name));
    obs[static_cast<size_t>(j)] = p;
    ++out.joints_used;
  }
  if (out.joints_used < 3)
    throw InvalidInput(fmt::format("pose from keypoints: {} keypoints of joints; at least 3 are needed", out.joints_used));

  out.params = start;
  // Scale from the observed bones.
  std::vector<Vec3> rest = shape_body(model, start.shape).joints;
  {
    double ratio = 0.0;
    int bones = 0;
    for (int j = 0; j < J; ++j) {
      const int p = model.parents[static_cast<size_t>(j)];
      if (p < 0 || !obs[static_cast<size_t>(j)] || !obs[static_cast<size_t>(p)]) continue;
      const double len = (rest[static_cast<size_t>(j)] - rest[static_cast<size_t>(p)]).norm();
      if (!(len > 1e-6)) continue;
      ratio += (*obs[static_cast<size_t>(j)] - *obs[static_cast<size_t>(p)]).norm() / len;
      ++bones;
    }
    const bool has_stature = model.num_shapes() == kNumMeasurements &&
                             model.shape_names[static_cast<size_t>(Measurement::Stature)] == "stature";
    if (bones >= 3 && has_stature) {
      out.scale = std::clamp(ratio / bones, 0.7, 1.3);
      const BodyMeasurements base = measure_body(model, shape_body(model, Eigen::VectorXd::Zero(model.num_shapes())));
      MeasurementTargets targets;
      targets.mm[static_cast<size_t>(Measurement::Stature)] = out.scale * base[static_cast<size_t>(Measurement::Stature)];
      out.params.shape = shape_from_measurements(model, targets).shape;
      rest = shape_body(model, out.params.shape).joints;
    }
  }

  // Children lists and, per joint, the observed frontier of its subtree.
  std::vector<std::vector<int>> children(static_cast<size_t>(J));
  for (int j = 1; j < J; ++j) children[static_cast<size_t>(model.parents[static_cast<size_t>(j)])].push_back(j);
  auto frontier = [&](int j) {
    std::vector<int> f, stack(children[static_cast<size_t>(j)].rbegin(), children[static_cast<size_t>(j)].rend());
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      if (obs[static_cast<size_t>(c)]) {
        f.push_back(c);
        continue;
      }
      for (auto it = children[static_cast<size_t>(c)].rbegin(); it != children[static_cast<size_t>(c)].rend(); ++it)
        stack.push_back(*it);
    }
    return f;
  };

  std::vector<Mat3> R(static_cast<size_t>(J));
  for (int j = 0; j < J; ++j) R[static_cast<size_t>(j)] = rotation_from_axis_angle(start.joint_rotations[static_cast<size_t>(j)]);
  Vec3 t = start.translation_mm;
  for (int j = 0; j < J; ++j) {
    const auto sj = static_cast<size_t>(j);
    const std::vector<int> targets = frontier(j);
    const Kinematics k = forward(model, rest, R, t);
    if (model.parents[sj] < 0) {
      std::vector<Vec3> from, to;
      std::vector<double> w;
      if (obs[sj]) {
        from.push_back(k.o[sj]);
        to.push_back(*obs[sj]);
        w.push_back(1.0);
      }
      for (int c : targets) {
        from.push_back(k.o[static_cast<size_t>(c)]);
        to.push_back(*obs[static_cast<size_t>(c)]);
        w.push_back(1.0);
      }
      if (from.empty()) continue;
      const RigidTransform T = rigid_align(from, to, w);
      R[sj] = T.rotation * R[sj];
      t = T.apply(k.o[sj]) - rest[sj];
      continue;
    }
    if (targets.empty()) continue;
    const Vec3& oj = k.o[sj];
    Mat3 G;
    if (targets.size() == 1) {
      const Vec3 a = k.o[static_cast<size_t>(targets[0])] - oj, b = *obs[static_cast<size_t>(targets[0])] - oj;
      if (!(a.norm() > 1e-9) || !(b.norm() > 1e-9)) continue;
      G = swing(a.normalized(), b.normalized());
    } else {
      Mat3 H = Mat3::Zero();
      for (int c : targets) {
        const Vec3 a = k.o[static_cast<size_t>(c)] - oj, b = *obs[static_cast<size_t>(c)] - oj;
        if (a.norm() > 1e-9 && b.norm() > 1e-9) H += b.normalized() * a.normalized().transpose();
      }
      G = nearest_rotation(H);
    }
    const Mat3& Qp = k.Q[static_cast<size_t>(model.parents[sj])];
    R[sj] = Qp.transpose() * G * Qp * R[sj];
  }
  for (int j = 0; j < J; ++j) out.params.joint_rotations[static_cast<size_t>(j)] = axis_angle_from_rotation(R[static_cast<size_t>(j)]);
  out.params.translation_mm = t;
  const Kinematics k = forward(model, rest, R, t);
  double sq = 0.0;
  for (int j = 0; j < J; ++j)
    if (obs[static_cast<size_t>(j)]) sq += (k.o[static_cast<size_t>(j)] - *obs[static_cast<size_t>(j)]).squaredNorm();
  out.rms_mm = std::sqrt(sq / out.joints_used);
  return out;
}

}  // namespace knitforge
