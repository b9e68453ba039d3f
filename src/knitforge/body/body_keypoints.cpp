#include "knitforge/body/body_keypoints.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

const std::array<std::string, kNumBodyKeypoints>& body_keypoint_names() {
  static const std::array<std::string, kNumBodyKeypoints> names = {
      "nose",      "neck",       "right_shoulder", "right_elbow", "right_wrist", "left_shoulder",
      "left_elbow", "left_wrist", "right_hip",      "right_knee",  "right_ankle", "left_hip",
      "left_knee", "left_ankle", "right_eye",      "left_eye",    "right_ear",   "left_ear"};
  return names;
}

namespace {

// The head vertex farthest along `direction` among those within `band` of
// height z.
int extreme_vertex(const std::vector<Vec3>& v, const std::vector<int>& head, const Vec3& centre,
                   const Vec3& direction, double z, double band) {
  int best = -1;
  double best_value = -std::numeric_limits<double>::infinity();
  for (int i : head) {
    const Vec3& p = v[static_cast<size_t>(i)];
    if (std::abs(p.z() - z) > band) continue;
    const double value = (p - centre).dot(direction);
    if (value > best_value) {
      best_value = value;
      best = i;
    }
  }
  return best;
}

}  // namespace

BodyKeypointRig body_keypoint_rig(const BodyModel& model) {
  BodyKeypointRig rig;
  rig.joint.fill(-1);
  rig.vertex.fill(-1);
  const auto& names = body_keypoint_names();
  for (int k = 0; k < kNumBodyKeypoints; ++k) {
    if (k == 0 || k >= 14) continue;  // face landmarks
    const int j = model.joint_index(names[static_cast<size_t>(k)]);
    if (j < 0)
      throw InvalidInput(fmt::format("body model '{}' has no joint '{}', which keypoint {} needs", model.name,
                                     names[static_cast<size_t>(k)], k));
    rig.joint[static_cast<size_t>(k)] = j;
  }
  const int head_joint = model.joint_index("head");
  if (head_joint < 0) throw InvalidInput(fmt::format("body model '{}' has no joint 'head' for the face keypoints", model.name));
  // Head vertices: largest skinning weight on the head joint.
  std::vector<int> head;
  for (int i = 0; i < model.num_vertices(); ++i) {
    int arg = -1;
    double best = -1.0;
    for (RowSparse::InnerIterator it(model.skinning_weights, i); it; ++it)
      if (it.value() > best) {
        best = it.value();
        arg = static_cast<int>(it.col());
      }
    if (arg == head_joint) head.push_back(i);
  }
  if (head.size() < 10)
    throw InvalidInput(fmt::format("body model '{}': only {} vertices follow the head joint; the face keypoints need "
                                   "a head",
                                   model.name, head.size()));
  const auto& v = model.template_vertices;
  Vec3 lo = v[static_cast<size_t>(head[0])], hi = lo;
  for (int i : head) {
    lo = lo.cwiseMin(v[static_cast<size_t>(i)]);
    hi = hi.cwiseMax(v[static_cast<size_t>(i)]);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double h = hi.z() - lo.z();
  const double band = 0.06 * h;
  const double side = std::sin(35.0 * std::numbers::pi / 180.0), front = std::cos(35.0 * std::numbers::pi / 180.0);
  // The body faces -y; its left is +x.
  rig.vertex[0] = extreme_vertex(v, head, centre, {0, -1, 0}, centre.z() - 0.05 * h, band);
  rig.vertex[14] = extreme_vertex(v, head, centre, {-side, -front, 0}, centre.z() + 0.08 * h, band);
  rig.vertex[15] = extreme_vertex(v, head, centre, {side, -front, 0}, centre.z() + 0.08 * h, band);
  rig.vertex[16] = extreme_vertex(v, head, centre, {-1, 0, 0}, centre.z(), band);
  rig.vertex[17] = extreme_vertex(v, head, centre, {1, 0, 0}, centre.z(), band);
  for (int k : {0, 14, 15, 16, 17})
    if (rig.vertex[static_cast<size_t>(k)] < 0)
      throw InvalidInput(fmt::format("body model '{}': no head vertex for the keypoint '{}'", model.name,
                                     names[static_cast<size_t>(k)]));
  return rig;
}

std::array<Vec3, kNumBodyKeypoints> body_keypoints(const BodyKeypointRig& rig, const PosedBody& posed) {
  std::array<Vec3, kNumBodyKeypoints> out;
  for (size_t k = 0; k < out.size(); ++k)
    out[k] = rig.joint[k] >= 0 ? posed.joints[static_cast<size_t>(rig.joint[k])]
                               : posed.vertices[static_cast<size_t>(rig.vertex[k])];
  return out;
}

Vec3 keypoint_pelvis(const std::array<Vec3, kNumBodyKeypoints>& keypoints) { return 0.5 * (keypoints[8] + keypoints[11]); }

}  // namespace knitforge
