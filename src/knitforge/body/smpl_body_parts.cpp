#include "knitforge/body/smpl_body_parts.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/smpl_model_npz.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// SMPL's joint order (smpl_joint_names()).
// clang-format off
enum SmplJoint : int {
  kPelvis = 0, kLHip, kRHip, kSpine1, kLKnee, kRKnee, kSpine2, kLAnkle, kRAnkle, kSpine3, kLFoot, kRFoot,
  kNeck, kLCollar, kRCollar, kHead, kLShoulder, kRShoulder, kLElbow, kRElbow, kLWrist, kRWrist,
  kNumBodyJoints  // 22: the body joints SMPL, SMPL+H and SMPL-X share
};
constexpr std::array<int, kNumBodyJoints> kSmplParents = {-1, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7,
                                                          8, 9, 9, 9, 12, 13, 14, 16, 17, 18, 19};
// clang-format on

// The bones whose length or direction the derivation uses.
constexpr std::array<std::array<int, 2>, 10> kUsedBones = {{{kNeck, kHead},
                                                            {kLShoulder, kLElbow},
                                                            {kRShoulder, kRElbow},
                                                            {kLElbow, kLWrist},
                                                            {kRElbow, kRWrist},
                                                            {kLHip, kLKnee},
                                                            {kRHip, kRKnee},
                                                            {kLKnee, kLAnkle},
                                                            {kRKnee, kRAnkle},
                                                            {kPelvis, kSpine1}}};

std::vector<Vec3> rest_joints(const BodyModel& m) {
  std::vector<Vec3> J(static_cast<size_t>(m.num_joints()), Vec3::Zero());
  for (int j = 0; j < m.joint_regressor.outerSize(); ++j)
    for (RowSparse::InnerIterator it(m.joint_regressor, j); it; ++it)
      J[static_cast<size_t>(j)] += it.value() * m.template_vertices[static_cast<size_t>(it.col())];
  return J;
}

// Joint j and all its descendants (parents precede children).
std::vector<char> subtree(const BodyModel& m, int root) {
  std::vector<char> in(static_cast<size_t>(m.num_joints()), 0);
  in[static_cast<size_t>(root)] = 1;
  for (int j = root + 1; j < m.num_joints(); ++j) {
    const int p = m.parents[static_cast<size_t>(j)];
    if (p >= 0 && in[static_cast<size_t>(p)]) in[static_cast<size_t>(j)] = 1;
  }
  return in;
}

// Each vertex's total skinning weight on the joints marked in `chain`.
std::vector<double> chain_weight(const BodyModel& m, const std::vector<char>& chain) {
  std::vector<double> w(static_cast<size_t>(m.num_vertices()), 0.0);
  for (int i = 0; i < m.skinning_weights.outerSize(); ++i)
    for (RowSparse::InnerIterator it(m.skinning_weights, i); it; ++it)
      if (chain[static_cast<size_t>(it.col())]) w[static_cast<size_t>(i)] += it.value();
  return w;
}

int closest_vertex(const std::vector<Vec3>& v, const Vec3& p) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(v.size()); ++i)
    if ((v[static_cast<size_t>(i)] - p).squaredNorm() < (v[static_cast<size_t>(best)] - p).squaredNorm())
      best = i;
  return best;
}

// The vertex with the largest (sign +1) or smallest (-1) z among those
// passing `in(p, widen)`; the band is widened (widen = 1, 2, 4, ...) until
// one passes. -1 if none does even at widen 64.
template <class Pred>
int extreme_z(const std::vector<Vec3>& v, double sign, Pred in) {
  for (double widen = 1.0; widen <= 64.0; widen *= 2.0) {
    int best = -1;
    for (int i = 0; i < static_cast<int>(v.size()); ++i) {
      const Vec3& p = v[static_cast<size_t>(i)];
      if (in(p, widen) && (best < 0 || sign * p.z() > sign * v[static_cast<size_t>(best)].z())) best = i;
    }
    if (best >= 0) return best;
  }
  return -1;
}

}  // namespace

std::string smpl_body_parts_missing(const BodyModel& m) {
  std::string missing;
  for (int j = 0; j < kNumBodyJoints; ++j) {
    const std::string& name = smpl_joint_names()[static_cast<size_t>(j)];
    if (j >= m.num_joints() || m.joint_names[static_cast<size_t>(j)] != name)
      missing += (missing.empty() ? "" : ", ") + name;
  }
  if (!missing.empty())
    return fmt::format(
        "its joints ({}: {}, ...) are not SMPL's body joints in SMPL's order (joint 0-21 must be "
        "pelvis .. right_wrist as in SMPL, SMPL+H and SMPL-X); missing or elsewhere: {}",
        m.num_joints(), m.joint_names.empty() ? "" : m.joint_names.front(), missing);
  for (int j = 1; j < kNumBodyJoints; ++j) {
    if (m.parents[static_cast<size_t>(j)] != kSmplParents[static_cast<size_t>(j)])
      return fmt::format("its kinematic tree is not SMPL's: joint {} ('{}') has parent {}, SMPL's is {}", j,
                         m.joint_names[static_cast<size_t>(j)], m.parents[static_cast<size_t>(j)],
                         kSmplParents[static_cast<size_t>(j)]);
  }
  const std::vector<Vec3> J = rest_joints(m);
  for (const auto& [a, b] : kUsedBones) {
    if (!((J[static_cast<size_t>(b)] - J[static_cast<size_t>(a)]).norm() > 1.0))
      return fmt::format(
          "its rest joints '{}' and '{}' are {:.2f} mm apart: that bone is needed to place the part "
          "boundaries",
          m.joint_names[static_cast<size_t>(a)], m.joint_names[static_cast<size_t>(b)],
          (J[static_cast<size_t>(b)] - J[static_cast<size_t>(a)]).norm());
  }
  const auto z = [&](int j) { return J[static_cast<size_t>(j)].z(); };
  const auto x = [&](int j) { return J[static_cast<size_t>(j)].x(); };
  if (!(z(kHead) > z(kNeck) && z(kNeck) > z(kPelvis) && z(kPelvis) > z(kLKnee) && z(kLKnee) > z(kLAnkle) &&
        z(kRKnee) > z(kRAnkle) && x(kLHip) > x(kRHip) && x(kLShoulder) > x(kRShoulder) &&
        x(kLWrist) > x(kLElbow) && x(kLElbow) > x(kLShoulder) && x(kRWrist) < x(kRElbow) &&
        x(kRElbow) < x(kRShoulder)))
    return "its rest pose is not an upright T-pose in knitforge's axes (z up, left side +x: head above neck "
           "above "
           "pelvis above knees above ankles, left joints at larger x, arms out to the sides)";
  return {};
}

void label_smpl_body(BodyModel& m) {
  const std::string missing = smpl_body_parts_missing(m);
  if (!missing.empty())
    throw InvalidInput(
        fmt::format("body model '{}' cannot be given part labels and landmarks: {}", m.name, missing));
  const std::vector<Vec3> J = rest_joints(m);
  const auto& v = m.template_vertices;
  const int V = m.num_vertices();
  auto jt = [&](int j) -> const Vec3& { return J[static_cast<size_t>(j)]; };
  auto len = [&](int a, int b) { return (jt(b) - jt(a)).norm(); };

  // Reference lines: the median plane x = xc; the coronal plane y = yc(z)
  // through the spine joints (piecewise linear in z, constant beyond).
  const double xc = jt(kPelvis).x();
  std::vector<std::array<double, 2>> spine;  // (z, y), by z
  for (int j : {kPelvis, kSpine1, kSpine2, kSpine3}) spine.push_back({jt(j).z(), jt(j).y()});
  std::sort(spine.begin(), spine.end());
  auto yc = [&](double z) {
    if (z <= spine.front()[0]) return spine.front()[1];
    for (size_t k = 0; k + 1 < spine.size(); ++k) {
      if (z <= spine[k + 1][0]) {
        const double span = spine[k + 1][0] - spine[k][0];
        const double t = span > 0.0 ? (z - spine[k][0]) / span : 1.0;
        return spine[k][1] + t * (spine[k + 1][1] - spine[k][1]);
      }
    }
    return spine.back()[1];
  };

  // Planes relative to the joints (the constants of generated_body.cpp's
  // part_fields_at(), as fractions of its bone lengths).
  const Vec3 up = Vec3::UnitZ();
  const double neck_head = jt(kHead).z() - jt(kNeck).z();
  // The head's lower boundary hangs from the head joint by a fixed 22 mm
  // (heads vary little with stature; as a fraction of the neck it would
  // slide up and down the face as the neck's length changes).
  const double head_z = jt(kHead).z() - 22.0;
  const double neck_z = jt(kNeck).z() - 0.0667 * neck_head;
  // The neck's sides: 1.75 times its half-width at the neck landmark's
  // height (the widest vertex within 15 mm of that height, inside the
  // shoulders).
  double neck_radius = 0.0;
  const double neck_level = jt(kNeck).z() + 0.375 * neck_head;
  const double shoulders_half = 0.5 * (jt(kLShoulder).x() - jt(kRShoulder).x());
  for (const Vec3& p : v)
    if (std::abs(p.z() - neck_level) < 15.0 && std::abs(p.x() - xc) < shoulders_half)
      neck_radius = std::max(neck_radius, std::abs(p.x() - xc));
  if (!(neck_radius > 0.0))
    throw InvalidInput(
        fmt::format("body model '{}' cannot be given part labels: no vertex at the neck's height ({:.0f} "
                    "mm) between the shoulders",
                    m.name, neck_level));
  const double neck_half_width = 1.75 * neck_radius;
  // The legs' cut passes 10.4 mm above the crotch (the lowest vertex near
  // the median plane above the knees) and rises outwards.
  const double knees_z = std::max(jt(kLKnee).z(), jt(kRKnee).z());
  const int crotch = extreme_z(v, -1.0, [&](const Vec3& p, double widen) {
    return std::abs(p.x() - xc) < 12.0 * widen && p.z() > knees_z;
  });
  if (crotch < 0)
    throw InvalidInput(fmt::format("body model '{}' cannot be given part labels: no crotch (no vertex near the median "
                                   "plane above the knees)",
                                   m.name));
  const double crotch_z = v[static_cast<size_t>(crotch)].z() + 10.4;

  // Each arm: its bone directions and "above" = up made perpendicular to
  // the upper arm (up itself for a horizontal arm).
  struct Arm {
    Vec3 shoulder, bone, above, wrist, forearm;
    double upper_len, fore_len;
  };
  auto arm = [&](int sh, int el, int wr) {
    const Vec3 b = (jt(el) - jt(sh)).normalized();
    return Arm{
        jt(sh),      b,          (up - up.dot(b) * b).normalized(), jt(wr), (jt(wr) - jt(el)).normalized(),
        len(sh, el), len(el, wr)};
  };
  const std::array<Arm, 2> arms = {arm(kLShoulder, kLElbow, kLWrist), arm(kRShoulder, kRElbow, kRWrist)};
  const std::array<double, 2> foot_z = {jt(kLAnkle).z() + 0.1045 * len(kLKnee, kLAnkle),
                                        jt(kRAnkle).z() + 0.1045 * len(kRKnee, kRAnkle)};

  // Skinning: each limb's chain from its first joint off the torso.
  auto chain = [&](std::initializer_list<int> roots) {
    std::vector<char> in(static_cast<size_t>(m.num_joints()), 0);
    for (int r : roots) {
      const auto s = subtree(m, r);
      for (size_t j = 0; j < in.size(); ++j) in[j] = in[j] || s[j];
    }
    return chain_weight(m, in);
  };
  const std::array<std::vector<double>, 2> w_arm = {chain({kLCollar}), chain({kRCollar})};
  const std::array<std::vector<double>, 2> w_hand = {chain({kLElbow}), chain({kRElbow})};
  const std::array<std::vector<double>, 2> w_leg = {chain({kLHip}), chain({kRHip})};
  const std::array<std::vector<double>, 2> w_foot = {chain({kLKnee}), chain({kRKnee})};
  const std::vector<double> w_head = chain({kNeck});
  constexpr double kWeightCap = 1000.0, kWeightFloor = 0.02;
  auto cap = [&](double f, const std::vector<double>& w, int i) {
    return std::min(f, kWeightCap * (w[static_cast<size_t>(i)] - kWeightFloor));
  };

  std::vector<std::vector<double>> fields(static_cast<size_t>(kNumBodyParts),
                                          std::vector<double>(static_cast<size_t>(V)));
  std::vector<BodyPart> parts(static_cast<size_t>(V), BodyPart::TorsoFront);
  for (int i = 0; i < V; ++i) {
    const Vec3& p = v[static_cast<size_t>(i)];
    const double y = p.y() - yc(p.z()), x = p.x() - xc;
    std::array<double, kNumBodyParts> g{};
    auto at = [&](BodyPart b) -> double& { return g[static_cast<size_t>(b)]; };
    const double head = cap(p.z() - head_z - 0.35 * y, w_head, i);
    const double neck = std::min({p.z() - neck_z - 0.3 * y, -head, neck_half_width - std::abs(x)});
    at(BodyPart::Head) = head;
    at(BodyPart::Neck) = neck;
    std::array<double, 2> arm_f{}, leg_f{};
    for (int s = 0; s < 2; ++s) {
      const Arm& a = arms[static_cast<size_t>(s)];
      const Vec3 d = p - a.shoulder;
      arm_f[static_cast<size_t>(s)] =
          cap(std::min(d.dot(a.bone) - 0.14 * d.dot(a.above) + 0.0093 * a.upper_len,
                       d.dot(a.above) + 0.571 * a.upper_len),
              w_arm[static_cast<size_t>(s)], i);
      const double past_wrist = (p - a.wrist).dot(a.forearm) - 0.0333 * a.fore_len;
      const BodyPart hand = s == 0 ? BodyPart::LeftHand : BodyPart::RightHand;
      const BodyPart sleeve = s == 0 ? BodyPart::LeftSleeve : BodyPart::RightSleeve;
      at(hand) = cap(std::min(arm_f[static_cast<size_t>(s)], past_wrist), w_hand[static_cast<size_t>(s)], i);
      at(sleeve) = std::min(arm_f[static_cast<size_t>(s)], -past_wrist);
      const double sx = s == 0 ? 1.0 : -1.0;
      leg_f[static_cast<size_t>(s)] =
          cap(std::min(crotch_z + 0.55 * sx * x - p.z(), sx * x), w_leg[static_cast<size_t>(s)], i);
      const double above_foot = p.z() - foot_z[static_cast<size_t>(s)];
      const BodyPart foot = s == 0 ? BodyPart::LeftFoot : BodyPart::RightFoot;
      const BodyPart leg = s == 0 ? BodyPart::LeftLeg : BodyPart::RightLeg;
      at(foot) = cap(std::min(leg_f[static_cast<size_t>(s)], -above_foot), w_foot[static_cast<size_t>(s)], i);
      at(leg) = std::min(leg_f[static_cast<size_t>(s)], above_foot);
    }
    const double torso = std::min({-head, -neck, -arm_f[0], -arm_f[1], -leg_f[0], -leg_f[1]});
    at(BodyPart::TorsoFront) = std::min(torso, -y);
    at(BodyPart::TorsoBack) = std::min(torso, y);
    int best = 0;
    for (int q = 0; q < kNumBodyParts; ++q) {
      fields[static_cast<size_t>(q)][static_cast<size_t>(i)] = g[static_cast<size_t>(q)];
      if (g[static_cast<size_t>(q)] > g[static_cast<size_t>(best)]) best = q;
    }
    parts[static_cast<size_t>(i)] = static_cast<BodyPart>(best);
  }
  std::array<int, kNumBodyParts> count{};
  for (BodyPart b : parts) ++count[static_cast<size_t>(b)];
  for (int q = 0; q < kNumBodyParts; ++q) {
    if (count[static_cast<size_t>(q)] == 0) {
      const std::string part = body_part_name(static_cast<BodyPart>(q));
      throw InvalidInput(
          fmt::format("body model '{}' cannot be given part labels: no vertex falls in the part '{}' "
                      "(the template does not have the proportions of a human body in a T-pose)",
                      m.name, part));
    }
  }

  // Landmarks.
  std::map<std::string, int> lm;
  lm["crotch"] = crotch;
  for (int s = 0; s < 2; ++s) {
    const double sx = s == 0 ? 1.0 : -1.0;
    const double sh = sx * (arms[static_cast<size_t>(s)].shoulder.x() - xc);
    lm[s == 0 ? "left_acromion" : "right_acromion"] = extreme_z(v, 1.0, [&](const Vec3& p, double widen) {
      const double out = sx * (p.x() - xc) - sh;
      return out >= -2.0 * widen && out <= 18.0 * widen;
    });
  }
  const double top =
      std::max_element(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) { return a.z() < b.z(); })->z();
  auto front = [&](double z, double dist) { return Vec3(xc, yc(z) + dist, z); };
  lm["left_elbow"] = closest_vertex(v, jt(kLElbow) + Vec3(0, 0, 90));
  lm["left_wrist"] = closest_vertex(v, jt(kLWrist) + Vec3(0, 0, 90));
  lm["left_upper_arm"] = closest_vertex(v, 0.5 * (jt(kLShoulder) + jt(kLElbow)) + Vec3(0, 0, 120));
  const double s1 = jt(kSpine1).z(), s3 = jt(kSpine3).z(), pz = jt(kPelvis).z();
  lm["chest"] = closest_vertex(v, front(s3, -400.0));
  lm["waist"] = closest_vertex(v, front(s1 - 0.0556 * (s3 - s1), -400.0));
  lm["hip"] = closest_vertex(v, front(pz - (s1 - pz) / 3.0, 400.0));
  lm["neck"] = closest_vertex(v, front(jt(kNeck).z() + 0.375 * neck_head, -300.0));
  lm["head"] = closest_vertex(v, front(jt(kHead).z() + 0.40625 * (top - jt(kHead).z()), -400.0));
  lm["left_thigh"] = closest_vertex(v, jt(kLHip) + 0.3 * (jt(kLKnee) - jt(kLHip)) + Vec3(250, 0, 0));
  lm["left_calf"] = closest_vertex(v, jt(kLKnee) + 0.3 * (jt(kLAnkle) - jt(kLKnee)) + Vec3(250, 0, 0));
  for (const auto& [name, i] : lm) {
    if (i < 0)
      throw InvalidInput(fmt::format("body model '{}': no vertex for the landmark '{}'", m.name, name));
  }
  m.vertex_parts = std::move(parts);
  m.part_fields = std::move(fields);
  m.landmarks = std::move(lm);
  m.labels_note.clear();
}

}  // namespace knitforge
