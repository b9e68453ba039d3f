#include "knitforge/body/generated_body.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "knitforge/body/body_measurements.h"
#include "knitforge/body/shape_body.h"
#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/isotropic_remesh.h"
#include "knitforge/geometry/marching_tetrahedra.h"
#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------
// The skeleton (T-pose, mm; z up, facing -y, left = +x).

enum J : int {
  kPelvis, kSpine1, kSpine2, kNeck, kHead,
  kLCollar, kLShoulder, kLElbow, kLWrist,
  kRCollar, kRShoulder, kRElbow, kRWrist,
  kLHip, kLKnee, kLAnkle, kRHip, kRKnee, kRAnkle,
  kNumJoints
};

const std::array<const char*, kNumJoints> kJointNames = {
    "pelvis",      "spine1",        "spine2",     "neck",        "head",
    "left_collar", "left_shoulder", "left_elbow", "left_wrist",  "right_collar",
    "right_shoulder", "right_elbow", "right_wrist", "left_hip",  "left_knee",
    "left_ankle",  "right_hip",     "right_knee", "right_ankle"};
const std::array<int, kNumJoints> kParents = {-1, 0, 1, 2, 3, 2, 5, 6, 7, 2, 9, 10, 11, 0, 13, 14, 0, 16, 17};

constexpr double kLegAbduction = 5.0 * kPi / 180.0;

struct Skeleton {
  std::array<Vec3, kNumJoints> joint;
  std::array<Vec3, kNumJoints> bone_end;  // the end of each joint's bone (child joint or leaf end)
};

Skeleton rest_skeleton() {
  Skeleton s;
  auto& j = s.joint;
  j[kPelvis] = {0, 0, 940};
  j[kSpine1] = {0, 0, 1090};
  j[kSpine2] = {0, 0, 1270};
  j[kNeck] = {0, 10, 1480};
  j[kHead] = {0, 10, 1600};
  j[kLCollar] = {40, 0, 1400};
  j[kLShoulder] = {180, 0, 1410};
  j[kLElbow] = {460, 0, 1410};
  j[kLWrist] = {700, 0, 1410};
  j[kLHip] = {90, 0, 910};
  const Vec3 d(std::sin(kLegAbduction), 0.0, -std::cos(kLegAbduction));
  j[kLKnee] = j[kLHip] + 440.0 * d;
  j[kLAnkle] = j[kLKnee] + 400.0 * d;
  auto mirror = [](const Vec3& p) { return Vec3(-p.x(), p.y(), p.z()); };
  j[kRCollar] = mirror(j[kLCollar]);
  j[kRShoulder] = mirror(j[kLShoulder]);
  j[kRElbow] = mirror(j[kLElbow]);
  j[kRWrist] = mirror(j[kLWrist]);
  j[kRHip] = mirror(j[kLHip]);
  j[kRKnee] = mirror(j[kLKnee]);
  j[kRAnkle] = mirror(j[kLAnkle]);
  auto& e = s.bone_end;
  e[kPelvis] = j[kSpine1];
  e[kSpine1] = j[kSpine2];
  e[kSpine2] = j[kNeck];
  e[kNeck] = j[kHead];
  e[kHead] = {0, 10, 1760};
  for (int side = 0; side < 2; ++side) {
    const int c = side ? kRCollar : kLCollar, sh = c + 1, el = c + 2, wr = c + 3;
    const double sx = side ? -1.0 : 1.0;
    e[c] = j[sh];
    e[sh] = j[el];
    e[el] = j[wr];
    e[wr] = j[wr] + Vec3(sx * 180.0, 0, 0);
    const int hip = side ? kRHip : kLHip, knee = hip + 1, ankle = hip + 2;
    e[hip] = j[knee];
    e[knee] = j[ankle];
    e[ankle] = Vec3(j[ankle].x(), -170.0, 30.0);
  }
  return s;
}

// ---------------------------------------------------------------------------
// The implicit surface.

enum Group : int { gTorso, gNeck, gHead, gLArm, gLHand, gRArm, gRHand, gLLeg, gLFoot, gRLeg, gRFoot, kNumGroups };

double smin(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The primitives' eval() are written out in scalars, in the operations and
// order of the Eigen expressions they replace (same bits; an Eigen sum of
// three is (x0 + x1) + x2): the grid and the projections evaluate them
// millions of times, and unoptimised Eigen temporaries made the built-in
// body take 6.5 s under the sanitizers, most of it here.
double norm3(double x, double y, double z) { return std::sqrt((x * x + y * y) + z * z); }

struct Ellipsoid {
  Vec3 c, r;
  double eval(const Vec3& p) const {
    const double qx = p.x() - c.x(), qy = p.y() - c.y(), qz = p.z() - c.z();
    const double rx = r.x(), ry = r.y(), rz = r.z();
    const double k0 = norm3(qx / rx, qy / ry, qz / rz);
    const double k1 = norm3(qx / (rx * rx), qy / (ry * ry), qz / (rz * rz));
    if (k1 <= 1e-12) return -r.minCoeff();
    return k0 * (k0 - 1.0) / k1;
  }
};

// A capsule along a -> b whose radius follows three control values at
// t = 0, tm, 1 (piecewise smooth).
struct TaperedCapsule {
  Vec3 a, b;
  double r0, rm, r1, tm = 0.5;
  double radius(double t) const {
    if (t <= tm) return r0 + (rm - r0) * smoothstep(0.0, tm, t);
    return rm + (r1 - rm) * smoothstep(tm, 1.0, t);
  }
  double eval(const Vec3& p) const {
    const double abx = b.x() - a.x(), aby = b.y() - a.y(), abz = b.z() - a.z();
    const double px = p.x() - a.x(), py = p.y() - a.y(), pz = p.z() - a.z();
    const double t = std::clamp(((px * abx + py * aby) + pz * abz) / ((abx * abx + aby * aby) + abz * abz), 0.0, 1.0);
    return norm3(p.x() - (a.x() + t * abx), p.y() - (a.y() + t * aby), p.z() - (a.z() + t * abz)) - radius(t);
  }
};

// The torso: superelliptic sections (half width a, front depth bf towards
// -y, back depth bb) lofted along z by cubic Hermite interpolation.
struct TorsoLoft {
  struct Level {
    double z, a, bf, bb;
  };
  std::vector<Level> levels;
  double exponent = 2.3;

  Level at(double z) const {
    z = std::clamp(z, levels.front().z, levels.back().z);
    size_t i = 0;
    while (i + 2 < levels.size() && z > levels[i + 1].z) ++i;
    const Level& p0 = levels[i];
    const Level& p1 = levels[i + 1];
    const double h = p1.z - p0.z, t = (z - p0.z) / h;
    auto slope = [&](size_t k, double Level::*f) {
      if (k == 0 || k + 1 == levels.size()) return 0.0;
      return (levels[k + 1].*f - levels[k - 1].*f) / (levels[k + 1].z - levels[k - 1].z);
    };
    auto herm = [&](double Level::*f) {
      const double m0 = slope(i, f) * h, m1 = slope(i + 1, f) * h;
      const double t2 = t * t, t3 = t2 * t;
      return (2 * t3 - 3 * t2 + 1) * (p0.*f) + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * (p1.*f) + (t3 - t2) * m1;
    };
    return {z, herm(&Level::a), herm(&Level::bf), herm(&Level::bb)};
  }

  double eval(const Vec3& p) const {
    const Level L = at(p.z());
    const double b = p.y() < 0.0 ? L.bf : L.bb;
    const double X = std::abs(p.x()) / L.a, Y = std::abs(p.y()) / b;
    const double e = exponent;
    const double rho = std::pow(std::pow(X, e) + std::pow(Y, e), 1.0 / e);
    double lat;
    if (rho < 1e-6) {
      lat = -std::min(L.a, b);
    } else {
      const double gx = std::pow(X, e - 1.0) / L.a, gy = std::pow(Y, e - 1.0) / b;
      const double g = std::pow(rho, 1.0 - e) * std::sqrt(gx * gx + gy * gy);
      lat = g > 1e-9 ? (rho - 1.0) / g : (rho - 1.0) * std::min(L.a, b);
    }
    const double below = levels.front().z - p.z(), above = p.z() - levels.back().z;
    const double dz = std::max({below, above, 0.0});
    if (dz > 0.0) return lat > 0.0 ? std::sqrt(lat * lat + dz * dz) : dz;
    return std::max({lat, below, above});
  }
};

class BodyImplicit {
 public:
  explicit BodyImplicit(const Skeleton& s) {
    torso_.levels = {{805, 115, 70, 85},  {880, 178, 102, 128}, {960, 172, 100, 118}, {1080, 150, 104, 96},
                     {1180, 160, 110, 100}, {1270, 176, 122, 112}, {1360, 176, 105, 110}, {1430, 160, 78, 92},
                     {1480, 85, 58, 68}};
    shoulders_ = {{-165, 8, 1415}, {165, 8, 1415}, 55, 55, 55};
    neck_ = {{0, 10, 1440}, {0, 5, 1610}, 60, 60, 60};
    head_ = {{0, 5, 1645}, {80, 100, 115}};
    jaw_ = {{0, -25, 1592}, {56, 60, 46}};
    for (int side = 0; side < 2; ++side) {
      const double sx = side ? -1.0 : 1.0;
      const int c = side ? kRCollar : kLCollar;
      const auto& j = s.joint;
      upper_[side] = {j[c + 1], j[c + 2], 54, 47, 39};
      fore_[side] = {j[c + 2], j[c + 3], 39, 41, 27, 0.25};
      hand_[side] = {j[c + 3] + Vec3(sx * 92.0, -4.0, -4.0), {95, 46, 18}};
      const int hip = side ? kRHip : kLHip;
      thigh_[side] = {j[hip], j[hip + 1], 95, 86, 58, 0.25};
      shin_[side] = {j[hip + 1], j[hip + 2], 57, 60, 35, 0.3};
      const double ax = j[hip + 2].x();
      foot_[side] = {{ax, -45, 32}, {45, 125, 42}};
      heel_[side] = {{ax, 40, 45}, {36, 42, 45}};
    }
  }

  /// f(p) (< 0 inside) and the group of the nearest primitive.
  double eval(const Vec3& p, int* group = nullptr) const {
    double best = 1e300;
    int owner = gTorso;
    auto note = [&](double d, int g) {
      if (d < best) {
        best = d;
        owner = g;
      }
      return d;
    };
    const double torso = smin(note(torso_.eval(p), gTorso), note(shoulders_.eval(p), gTorso), 35.0);
    const double head = smin(note(head_.eval(p), gHead), note(jaw_.eval(p), gHead), 20.0);
    double f = smin(torso, smin(note(neck_.eval(p), gNeck), head, 22.0), 25.0);
    double legs = 1e300;
    for (int side = 0; side < 2; ++side) {
      const int ga = side ? gRArm : gLArm, gh = side ? gRHand : gLHand;
      const int gl = side ? gRLeg : gLLeg, gf = side ? gRFoot : gLFoot;
      double arm = 1e300;
      if (std::abs(p.x()) > 100.0 && (side ? p.x() < 0 : p.x() > 0)) {
        arm = smin(note(upper_[side].eval(p), ga), note(fore_[side].eval(p), ga), 15.0);
        arm = smin(arm, note(hand_[side].eval(p), gh), 10.0);
      }
      if (arm < 1e299) f = smin(f, arm, 30.0);
      if (p.z() < 1050.0 && (side ? p.x() < 60 : p.x() > -60)) {
        double leg = smin(note(thigh_[side].eval(p), gl), note(shin_[side].eval(p), gl), 20.0);
        double foot = smin(note(foot_[side].eval(p), gf), note(heel_[side].eval(p), gf), 15.0);
        foot = std::max(foot, -p.z());  // flat sole on the floor
        leg = smin(leg, foot, 15.0);
        legs = std::min(legs, leg);
      }
    }
    if (legs < 1e299) f = smin(f, legs, 25.0);
    if (group) *group = owner;
    return f;
  }

 private:
  TorsoLoft torso_;
  TaperedCapsule shoulders_, neck_;
  Ellipsoid head_, jaw_;
  std::array<TaperedCapsule, 2> upper_, fore_, thigh_, shin_;
  std::array<Ellipsoid, 2> hand_, foot_, heel_;
};

Vec3 gradient(const BodyImplicit& f, const Vec3& p) {
  const double h = 0.25;
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 a = p, b = p;
    a[k] += h;
    b[k] -= h;
    g[k] = (f.eval(a) - f.eval(b)) / (2 * h);
  }
  return g;
}

Vec3 project(const BodyImplicit& f, Vec3 p) {
  for (int it = 0; it < 6; ++it) {
    const double v = f.eval(p);
    if (std::abs(v) < 1e-4) break;
    const Vec3 g = gradient(f, p);
    const double g2 = g.squaredNorm();
    if (g2 < 1e-12) break;
    Vec3 step = v * g / g2;
    if (step.norm() > 5.0) step *= 5.0 / step.norm();
    p -= step;
  }
  return p;
}

// ---------------------------------------------------------------------------
// Skinning: bone heat.

// Joints a vertex of a group may be bound to (its limb's bones).
std::vector<int> allowed_joints(int group) {
  switch (group) {
    case gTorso: return {kPelvis, kSpine1, kSpine2, kNeck, kLCollar, kRCollar, kLHip, kRHip};
    case gNeck: return {kNeck, kSpine2, kHead};
    case gHead: return {kHead, kNeck};
    case gLArm: return {kLCollar, kLShoulder, kLElbow, kLWrist};
    case gLHand: return {kLWrist, kLElbow};
    case gRArm: return {kRCollar, kRShoulder, kRElbow, kRWrist};
    case gRHand: return {kRWrist, kRElbow};
    case gLLeg: return {kPelvis, kLHip, kLKnee, kLAnkle};
    case gLFoot: return {kLAnkle, kLKnee};
    case gRLeg: return {kPelvis, kRHip, kRKnee, kRAnkle};
    default: return {kRAnkle, kRKnee};
  }
}

// Bone segments of a joint (the pelvis and spine2 have several).
std::vector<std::array<Vec3, 2>> bones_of(const Skeleton& s, int j) {
  if (j == kPelvis) return {{s.joint[kPelvis], s.joint[kSpine1]}, {s.joint[kPelvis], s.joint[kLHip]}, {s.joint[kPelvis], s.joint[kRHip]}};
  if (j == kSpine2) return {{s.joint[kSpine2], s.joint[kNeck]}, {s.joint[kSpine2], s.joint[kLCollar]}, {s.joint[kSpine2], s.joint[kRCollar]}};
  return {{s.joint[static_cast<size_t>(j)], s.bone_end[static_cast<size_t>(j)]}};
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - a - t * ab).norm();
}

RowSparse bone_heat_weights(const TriMesh& mesh, const std::vector<int>& group, const Skeleton& s) {
  const int V = mesh.num_vertices();
  const SparseMatrix L = cotan_laplacian(mesh);
  const std::vector<double> area = mixed_voronoi_areas(mesh);
  std::vector<double> heat(static_cast<size_t>(V));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(V, kNumJoints);
  for (int i = 0; i < V; ++i) {
    const Vec3& p = mesh.vertices[static_cast<size_t>(i)];
    double best = 1e300;
    int bj = -1;
    for (int j : allowed_joints(group[static_cast<size_t>(i)])) {
      for (const auto& seg : bones_of(s, j)) {
        const double d = segment_distance(p, seg[0], seg[1]);
        if (d < best - 1e-9) {
          best = d;
          bj = j;
        }
      }
    }
    const double h = area[static_cast<size_t>(i)] / std::max(best * best, 1.0);
    heat[static_cast<size_t>(i)] = h;
    rhs(i, bj) = h;
  }
  SparseMatrix A = L;
  for (int i = 0; i < V; ++i) A.coeffRef(i, i) += heat[static_cast<size_t>(i)];
  // Simplicial: the built-in body is bit-identical on every machine (sparse_solver.h).
  const SparseSolver solver(A, FactorMode::Simplicial);
  const Eigen::MatrixXd W = solver.solve_columns(rhs);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < V; ++i) {
    std::vector<std::pair<double, int>> w;
    for (int j = 0; j < kNumJoints; ++j)
      if (W(i, j) > 0.0) w.emplace_back(W(i, j), j);
    std::sort(w.begin(), w.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
    if (w.size() > 4) w.resize(4);
    double sum = 0.0;
    for (const auto& [x, j] : w) sum += x;
    std::vector<std::pair<double, int>> kept;
    for (const auto& [x, j] : w)
      if (x >= 0.01 * sum) kept.emplace_back(x, j);
    sum = 0.0;
    for (const auto& [x, j] : kept) sum += x;
    if (!(sum > 0.0)) throw SolverError(fmt::format("generated body: vertex {} got no skinning weight", i));
    for (const auto& [x, j] : kept) t.emplace_back(i, j, x / sum);
  }
  RowSparse weights(V, kNumJoints);
  weights.setFromTriplets(t.begin(), t.end());
  return weights;
}

// ---------------------------------------------------------------------------
// The shape rig: internal parameters (scales), linear in every one.

enum Param : int {
  pStature, pLeg, pArm, pShoulder, pChest, pWaist, pHip, pNeck, pUpperArm, pThigh, pCalf, pHeadGirth, kNumParams
};
// Shape parameter k is measurement k (same order as body_measurements.h).
static_assert(kNumParams == kNumMeasurements);

double torso_sigma(double z, const std::array<double, kNumParams>& s) {
  const double hip = 1.0 - smoothstep(900.0, 1080.0, z);
  const double waist = smoothstep(900.0, 1080.0, z) * (1.0 - smoothstep(1080.0, 1270.0, z));
  const double chest = smoothstep(1080.0, 1270.0, z) * (1.0 - smoothstep(1380.0, 1480.0, z));
  return s[pHip] * hip + s[pWaist] * waist + s[pChest] * chest;
}

// How much of the torso girth scaling a rest point takes: 1 on the torso,
// fading out into the arms (at arm height, beyond the shoulders) and down
// the thighs. A field of the rest position, not of the skinning weights, so
// that the girths bend the surface smoothly across the bones' regions.
double torso_membership(const Vec3& x) {
  const double arm_height = smoothstep(1220.0, 1400.0, x.z());
  const double lateral = 1.0 - arm_height * smoothstep(120.0, 260.0, std::abs(x.x()));
  return lateral * smoothstep(700.0, 830.0, x.z());
}

// The torso girth displacement of a rest point: its section scaled about
// the body's vertical axis, as much as the point belongs to the torso.
Vec3 torso_displacement(const Vec3& x, const std::array<double, kNumParams>& s) {
  return torso_sigma(x.z(), s) * torso_membership(x) * Vec3(x.x(), x.y(), 0.0);
}

// Where the limbs sit on the torso (collars: the arms, hips: the legs): they
// move with the torso's girth there, and their subtrees with them.
std::array<Vec3, kNumJoints> girth_shifts(const Skeleton& sk, const std::array<double, kNumParams>& s) {
  std::array<Vec3, kNumJoints> shift{};
  for (int j = 0; j < kNumJoints; ++j) {
    const int p = kParents[static_cast<size_t>(j)];
    shift[static_cast<size_t>(j)] = p < 0 ? Vec3::Zero() : shift[static_cast<size_t>(p)];
    if (j == kLCollar || j == kRCollar || j == kLHip || j == kRHip)
      shift[static_cast<size_t>(j)] = torso_displacement(sk.joint[static_cast<size_t>(j)], s);
  }
  return shift;
}

// Rest joints for internal parameters s (linear in s).
std::array<Vec3, kNumJoints> rig_joints(const Skeleton& sk, const std::array<double, kNumParams>& s) {
  std::array<double, kNumJoints> scale{};
  scale.fill(1.0);
  // The stature stretches the torso, neck and head vertically (the collars'
  // height too, not their width).
  std::array<bool, kNumJoints> vertical{};
  for (int j : {kSpine1, kSpine2, kNeck, kHead, kLCollar, kRCollar}) vertical[static_cast<size_t>(j)] = true;
  for (int j : {kLKnee, kLAnkle, kRKnee, kRAnkle}) scale[static_cast<size_t>(j)] += s[pLeg];
  for (int j : {kLElbow, kLWrist, kRElbow, kRWrist}) scale[static_cast<size_t>(j)] += s[pArm];
  for (int j : {kLShoulder, kRShoulder}) scale[static_cast<size_t>(j)] += s[pShoulder];
  std::array<Vec3, kNumJoints> J{};
  const double leg_height = sk.joint[kLHip].z() - sk.joint[kLAnkle].z();
  J[kPelvis] = sk.joint[kPelvis] + Vec3(0, 0, s[pLeg] * leg_height);
  for (int j = 1; j < kNumJoints; ++j) {
    const int p = kParents[static_cast<size_t>(j)];
    Vec3 offset = scale[static_cast<size_t>(j)] * (sk.joint[static_cast<size_t>(j)] - sk.joint[static_cast<size_t>(p)]);
    if (vertical[static_cast<size_t>(j)]) offset.z() *= 1.0 + s[pStature];
    J[static_cast<size_t>(j)] = J[static_cast<size_t>(p)] + offset;
  }
  const auto shift = girth_shifts(sk, s);
  for (int j = 0; j < kNumJoints; ++j) J[static_cast<size_t>(j)] += shift[static_cast<size_t>(j)];
  return J;
}

// Radial scale profile of a limb bone along t (the girth parameters).
double limb_sigma(int j, double t, const std::array<double, kNumParams>& s) {
  switch (j) {
    case kNeck: return s[pNeck] * smoothstep(-0.6, 0.0, t) * (1.0 - smoothstep(0.6, 1.0, t));
    case kHead: return s[pHeadGirth];
    case kLShoulder:
    case kRShoulder: return s[pUpperArm] * smoothstep(0.0, 0.3, t) * (1.0 - smoothstep(0.7, 1.0, t));
    case kLHip:
    case kRHip: return s[pThigh] * (1.0 - smoothstep(0.45, 0.9, t));
    case kLKnee:
    case kRKnee: return s[pCalf] * smoothstep(0.0, 0.25, t) * (1.0 - smoothstep(0.45, 0.8, t));
    default: return 0.0;
  }
}


bool is_torso_joint(int j) { return j == kPelvis || j == kSpine1 || j == kSpine2; }


// The torso's vertical map: piecewise linear through the spine chain, the
// last segment's stretch continued above the neck joint (as the neck bone's
// is: no kink where the two regions' weights meet), a translation below the
// pelvis.
double torso_z(const Vec3& x, const Skeleton& sk, const std::array<Vec3, kNumJoints>& J) {
    const int chain[4] = {kPelvis, kSpine1, kSpine2, kNeck};
    double z;
    if (x.z() <= sk.joint[kPelvis].z()) {
      z = x.z() + J[kPelvis].z() - sk.joint[kPelvis].z();
    } else if (x.z() >= sk.joint[kNeck].z()) {
      const double ratio = (J[kNeck].z() - J[kSpine2].z()) / (sk.joint[kNeck].z() - sk.joint[kSpine2].z());
      z = J[kNeck].z() + ratio * (x.z() - sk.joint[kNeck].z());
    } else {
      int k = 0;
      while (x.z() > sk.joint[static_cast<size_t>(chain[k + 1])].z()) ++k;
      const double z0 = sk.joint[static_cast<size_t>(chain[k])].z(), z1 = sk.joint[static_cast<size_t>(chain[k + 1])].z();
      const double t = (x.z() - z0) / (z1 - z0);
      z = J[static_cast<size_t>(chain[k])].z() + t * (J[static_cast<size_t>(chain[k + 1])].z() - J[static_cast<size_t>(chain[k])].z());
    }
  return z;
}

// Where joint j's map sends rest point x for internal parameters s.
Vec3 joint_map(int j, const Vec3& x, const Skeleton& sk, const std::array<Vec3, kNumJoints>& J,
               const std::array<double, kNumParams>& s) {
  if (is_torso_joint(j)) {
    // The girths are torso_displacement(), added in rig_vertices().
    return {x.x(), x.y(), torso_z(x, sk, J)};
  }
  const Vec3 a0 = sk.joint[static_cast<size_t>(j)], b0 = sk.bone_end[static_cast<size_t>(j)];
  const Vec3 u = b0 - a0;
  const double t = (x - a0).dot(u) / u.squaredNorm();
  const Vec3 r = x - a0 - t * u;
  const Vec3 a = J[static_cast<size_t>(j)];
  // The bone's far end: the child joint, or the leaf end moved rigidly.
  Vec3 b = a + u;
  for (int c = 0; c < kNumJoints; ++c) {
    if (kParents[static_cast<size_t>(c)] == j && (sk.joint[static_cast<size_t>(c)] - b0).norm() < 1e-9) b = J[static_cast<size_t>(c)];
  }
  Vec3 y = a + t * (b - a) + (1.0 + limb_sigma(j, t, s)) * r;
  // The collars sit in the torso: vertically they follow its map, so that
  // the stature stretches the shoulders' tops like the rest of the torso.
  if (j == kLCollar || j == kRCollar) y.z() += torso_z(x, sk, J) - x.z() - (a.z() - a0.z());
  return y;
}

std::vector<Vec3> rig_vertices(const std::vector<Vec3>& rest, const RowSparse& weights, const Skeleton& sk,
                               const std::array<double, kNumParams>& s) {
  const auto J = rig_joints(sk, s);
  const auto shift = girth_shifts(sk, s);
  std::vector<Vec3> out(rest.size(), Vec3::Zero());
  for (int i = 0; i < static_cast<int>(rest.size()); ++i) {
    const Vec3& x = rest[static_cast<size_t>(i)];
    Vec3 carried = Vec3::Zero();  // the limbs' girth shifts the joint maps apply
    for (RowSparse::InnerIterator it(weights, i); it; ++it) {
      out[static_cast<size_t>(i)] += it.value() * joint_map(static_cast<int>(it.col()), x, sk, J, s);
      carried += it.value() * shift[static_cast<size_t>(it.col())];
    }
    // On the torso the torso's displacement replaces the limbs' shifts,
    // blended by the membership (1 on the torso, 0 out on the limbs).
    out[static_cast<size_t>(i)] += torso_displacement(x, s) - torso_membership(x) * carried;
  }
  return out;
}

// ---------------------------------------------------------------------------
// Joint regressor: min-norm weights on nearby vertices, exact on the template
// and on every shape direction.

RowSparse exact_regressor(const std::vector<Vec3>& rest, const Eigen::MatrixXd& basis, const std::array<Vec3, kNumJoints>& J0,
                          const Eigen::MatrixXd& dJ) {
  const int V = static_cast<int>(rest.size()), K = static_cast<int>(basis.cols());
  const int n = std::min(V, 150);
  std::vector<Eigen::Triplet<double>> trip;
  for (int j = 0; j < kNumJoints; ++j) {
    std::vector<std::pair<double, int>> near(static_cast<size_t>(V));
    for (int i = 0; i < V; ++i) near[static_cast<size_t>(i)] = {(rest[static_cast<size_t>(i)] - J0[static_cast<size_t>(j)]).squaredNorm(), i};
    std::partial_sort(near.begin(), near.begin() + n, near.end());
    const int rows = 4 + 3 * K;
    Eigen::MatrixXd A(rows, n);
    Eigen::VectorXd b(rows);
    for (int c = 0; c < n; ++c) {
      const int i = near[static_cast<size_t>(c)].second;
      A(0, c) = 1.0;
      A.block<3, 1>(1, c) = rest[static_cast<size_t>(i)];
      for (int k = 0; k < K; ++k) A.block<3, 1>(4 + 3 * k, c) = basis.block<3, 1>(3 * i, k);
    }
    b(0) = 1.0;
    b.segment<3>(1) = J0[static_cast<size_t>(j)];
    for (int k = 0; k < K; ++k) b.segment<3>(4 + 3 * k) = dJ.block<3, 1>(3 * j, k);
    // Rows in mm are scaled to unit size so that the solve is balanced.
    Eigen::VectorXd rs = A.rowwise().norm().cwiseMax(1e-12).cwiseInverse();
    rs(0) = 1.0;
    const Eigen::MatrixXd As = rs.asDiagonal() * A;
    const Eigen::VectorXd bs = rs.asDiagonal() * b;
    const Eigen::VectorXd w0 = Eigen::VectorXd::Constant(n, 1.0 / n);
    // The shape rows are partly dependent (e.g. a limb's length changes are
    // affine near its joint, hence combinations of the position rows): the
    // SVD drops those directions, whose right-hand sides agree (checked).
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(As, Eigen::ComputeThinU | Eigen::ComputeThinV);
    svd.setThreshold(1e-10);
    const Eigen::VectorXd w = w0 + svd.solve(bs - As * w0);
    const double err = (A * w - b).cwiseAbs().maxCoeff();
    if (!(err < 1e-6))
      throw SolverError(fmt::format("generated body: the joint regressor of '{}' is not exact ({} mm)", kJointNames[static_cast<size_t>(j)], err));
    for (int c = 0; c < n; ++c)
      if (std::abs(w(c)) > 1e-12) trip.emplace_back(j, near[static_cast<size_t>(c)].second, w(c));
  }
  RowSparse R(kNumJoints, V);
  R.setFromTriplets(trip.begin(), trip.end());
  return R;
}

// ---------------------------------------------------------------------------
// Parts, fields, landmarks (rest coordinates of the template).

std::array<double, kNumBodyParts> part_fields_at(const Vec3& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  std::array<double, kNumBodyParts> g{};
  auto at = [&](BodyPart b) -> double& { return g[static_cast<size_t>(b)]; };
  const double head = z - (1578.0 + 0.35 * y);
  const double neck = std::min({z - (1472.0 + 0.3 * y), -head, 105.0 - std::abs(x)});
  const double arm_l = std::min((x - 176.0) - 0.14 * (z - 1400.0), z - 1250.0);
  const double arm_r = std::min((-x - 176.0) - 0.14 * (z - 1400.0), z - 1250.0);
  const double leg_l = std::min(805.0 + 0.55 * x - z, x);
  const double leg_r = std::min(805.0 - 0.55 * x - z, -x);
  at(BodyPart::Head) = head;
  at(BodyPart::Neck) = neck;
  at(BodyPart::LeftHand) = std::min(arm_l, x - 708.0);
  at(BodyPart::LeftSleeve) = std::min(arm_l, 708.0 - x);
  at(BodyPart::RightHand) = std::min(arm_r, -x - 708.0);
  at(BodyPart::RightSleeve) = std::min(arm_r, 708.0 + x);
  at(BodyPart::LeftFoot) = std::min(leg_l, 115.0 - z);
  at(BodyPart::LeftLeg) = std::min(leg_l, z - 115.0);
  at(BodyPart::RightFoot) = std::min(leg_r, 115.0 - z);
  at(BodyPart::RightLeg) = std::min(leg_r, z - 115.0);
  const double torso = std::min({-head, -neck, -arm_l, -arm_r, -leg_l, -leg_r});
  at(BodyPart::TorsoFront) = std::min(torso, -y);
  at(BodyPart::TorsoBack) = std::min(torso, y);
  return g;
}

int closest_vertex(const std::vector<Vec3>& v, const Vec3& p) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(v.size()); ++i)
    if ((v[static_cast<size_t>(i)] - p).squaredNorm() < (v[static_cast<size_t>(best)] - p).squaredNorm()) best = i;
  return best;
}

std::map<std::string, int> find_landmarks(const std::vector<Vec3>& v, const Skeleton& sk) {
  std::map<std::string, int> lm;
  int crotch = -1;
  for (int i = 0; i < static_cast<int>(v.size()); ++i) {
    const Vec3& p = v[static_cast<size_t>(i)];
    if (std::abs(p.x()) < 12.0 && p.z() > 500.0 && (crotch < 0 || p.z() < v[static_cast<size_t>(crotch)].z())) crotch = i;
  }
  if (crotch < 0) throw SolverError("generated body: no crotch vertex found");
  lm["crotch"] = crotch;
  for (int side = 0; side < 2; ++side) {
    const double sx = side ? -1.0 : 1.0;
    const std::string pre = side ? "right_" : "left_";
    int top = -1;
    for (int i = 0; i < static_cast<int>(v.size()); ++i) {
      const Vec3& p = v[static_cast<size_t>(i)];
      if (sx * p.x() >= 178.0 && sx * p.x() <= 198.0 && (top < 0 || p.z() > v[static_cast<size_t>(top)].z())) top = i;
    }
    lm[pre + "acromion"] = top;
  }
  const auto& j = sk.joint;
  lm["left_elbow"] = closest_vertex(v, j[kLElbow] + Vec3(0, 0, 90));
  lm["left_wrist"] = closest_vertex(v, j[kLWrist] + Vec3(0, 0, 90));
  lm["left_upper_arm"] = closest_vertex(v, 0.5 * (j[kLShoulder] + j[kLElbow]) + Vec3(0, 0, 120));
  lm["chest"] = closest_vertex(v, {0, -400, 1270});
  lm["waist"] = closest_vertex(v, {0, -400, 1080});
  lm["hip"] = closest_vertex(v, {0, 400, 890});
  lm["neck"] = closest_vertex(v, {0, -300, 1525});
  lm["head"] = closest_vertex(v, {0, -400, 1665});
  const Vec3 thigh = j[kLHip] + 0.3 * (j[kLKnee] - j[kLHip]);
  lm["left_thigh"] = closest_vertex(v, thigh + Vec3(250, 0, 0));
  const Vec3 calf = j[kLKnee] + 0.3 * (j[kLAnkle] - j[kLKnee]);
  lm["left_calf"] = closest_vertex(v, calf + Vec3(250, 0, 0));
  return lm;
}

}  // namespace

std::vector<std::string> generated_body_joint_names() { return {kJointNames.begin(), kJointNames.end()}; }

BodyModel make_generated_body(const GeneratedBodyOptions& options) {
  if (!(options.edge_length >= 8.0 && options.edge_length <= 60.0))
    throw InvalidInput(fmt::format("generated body: edge length {} mm must be within [8, 60]", options.edge_length));
  if (options.remesh_iterations < 1)
    throw InvalidInput(fmt::format("generated body: remesh iterations {} must be at least 1", options.remesh_iterations));
  const Skeleton sk = rest_skeleton();
  const BodyImplicit implicit(sk);
  const ImplicitFunction f = [&](const Vec3& p) { return implicit.eval(p); };
  BoundingBox box;
  box.min = {-910, -210, -20};
  box.max = {910, 180, 1785};
  const double cell = std::min(10.0, 0.7 * options.edge_length);
  TriMesh raw = largest_component(marching_tetrahedra(f, box, cell));
  RemeshOptions ro;
  ro.target_edge_length = options.edge_length;
  ro.iterations = options.remesh_iterations;
  ro.project = [&](const Vec3& p) { return project(implicit, p); };
  TriMesh mesh = isotropic_remesh(raw, ro);
  const SurfaceReport report = validate_surface(mesh);
  if (!report.ok() || report.num_components != 1 || report.num_boundary_loops != 0 || report.genus != 0)
    throw SolverError("generated body: the surface is not one closed genus-0 surface: " + report.summary());

  const int V = mesh.num_vertices();
  std::vector<int> group(static_cast<size_t>(V));
  for (int i = 0; i < V; ++i) implicit.eval(mesh.vertices[static_cast<size_t>(i)], &group[static_cast<size_t>(i)]);

  BodyModel m;
  m.name = "knitforge-body";
  m.template_vertices = mesh.vertices;
  m.faces = mesh.faces;
  m.parents.assign(kParents.begin(), kParents.end());
  m.joint_names = generated_body_joint_names();
  m.skinning_weights = bone_heat_weights(mesh, group, sk);

  // Shape basis (internal units), exact because the rig is linear.
  std::array<double, kNumParams> zero{};
  const auto J0 = rig_joints(sk, zero);
  Eigen::MatrixXd basis(3 * V, kNumParams);
  Eigen::MatrixXd dJ(3 * kNumJoints, kNumParams);
  for (int k = 0; k < kNumParams; ++k) {
    std::array<double, kNumParams> s{};
    s[static_cast<size_t>(k)] = 1.0;
    const auto moved = rig_vertices(m.template_vertices, m.skinning_weights, sk, s);
    const auto base = rig_vertices(m.template_vertices, m.skinning_weights, sk, zero);
    for (int i = 0; i < V; ++i) basis.block<3, 1>(3 * i, k) = moved[static_cast<size_t>(i)] - base[static_cast<size_t>(i)];
    const auto Jk = rig_joints(sk, s);
    for (int j = 0; j < kNumJoints; ++j) dJ.block<3, 1>(3 * j, k) = Jk[static_cast<size_t>(j)] - J0[static_cast<size_t>(j)];
  }
  m.shape_basis = basis;
  for (int k = 0; k < kNumParams; ++k) m.shape_names.push_back(measurement_info(static_cast<Measurement>(k)).key);
  m.joint_regressor = exact_regressor(m.template_vertices, basis, J0, dJ);

  m.vertex_parts.resize(static_cast<size_t>(V));
  m.part_fields.assign(static_cast<size_t>(kNumBodyParts), std::vector<double>(static_cast<size_t>(V)));
  for (int i = 0; i < V; ++i) {
    const auto g = part_fields_at(m.template_vertices[static_cast<size_t>(i)]);
    int best = 0;
    for (int q = 0; q < kNumBodyParts; ++q) {
      m.part_fields[static_cast<size_t>(q)][static_cast<size_t>(i)] = g[static_cast<size_t>(q)];
      if (g[static_cast<size_t>(q)] > g[static_cast<size_t>(best)]) best = q;
    }
    m.vertex_parts[static_cast<size_t>(i)] = static_cast<BodyPart>(best);
  }
  m.landmarks = find_landmarks(m.template_vertices, sk);

  // Normalise every shape column to +1 mm of its own measurement.
  const double eps = 0.01;
  for (int k = 0; k < kNumParams; ++k) {
    Eigen::VectorXd sp = Eigen::VectorXd::Zero(kNumParams), sm = sp;
    sp(k) = eps;
    sm(k) = -eps;
    const double dm = (measure_body(m, shape_body(m, sp))[static_cast<size_t>(k)] -
                       measure_body(m, shape_body(m, sm))[static_cast<size_t>(k)]) /
                      (2 * eps);
    if (!(std::abs(dm) > 1e-6))
      throw SolverError(fmt::format("generated body: shape parameter '{}' does not change its measurement", m.shape_names[static_cast<size_t>(k)]));
    m.shape_basis.col(k) /= dm;
  }
  // The regressor stays exact: the columns and the joint derivatives scale alike.
  validate_body_model(m);
  return m;
}

const BodyModel& generated_body() {
  static const BodyModel model = make_generated_body();
  return model;
}

}  // namespace knitforge
