#include "knitforge/body/body_measurements.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

const std::array<MeasurementInfo, kNumMeasurements> kInfo = {{
    {"stature", "height", "body height (stature)", false},
    {"inside_leg_length", "inside-leg", "inside leg length", false},
    {"arm_length", "arm-length", "arm length", false},
    {"shoulder_width", "shoulder-width", "shoulder width (biacromial)", false},
    {"chest_girth", "chest", "chest girth", true},
    {"waist_girth", "waist", "waist girth", true},
    {"hip_girth", "hip", "hip girth", true},
    {"neck_girth", "neck", "neck girth", true},
    {"upper_arm_girth", "upper-arm", "upper arm girth", true},
    {"thigh_girth", "thigh", "thigh girth", true},
    {"calf_girth", "calf", "calf girth", true},
    {"head_girth", "head", "head girth", true},
}};

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain; counter-clockwise hull without repeated end point.
std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

double perimeter(const std::vector<Vec2>& h) {
  double s = 0.0;
  for (size_t i = 0; i < h.size(); ++i) s += (h[(i + 1) % h.size()] - h[i]).norm();
  return s;
}

// Signed distance of q from the hull (negative inside); hull counter-clockwise.
double hull_outside_distance(const std::vector<Vec2>& h, const Vec2& q) {
  if (h.size() < 3) return 1e300;
  double worst = -1e300;
  for (size_t i = 0; i < h.size(); ++i) {
    const Vec2 e = h[(i + 1) % h.size()] - h[i];
    const double len = e.norm();
    if (len <= 0.0) continue;
    const Vec2 out(e.y() / len, -e.x() / len);
    worst = std::max(worst, out.dot(q - h[i]));
  }
  return worst;
}

int landmark(const BodyModel& model, const char* name) {
  const auto it = model.landmarks.find(name);
  if (it == model.landmarks.end())
    throw InvalidInput(fmt::format("body model '{}' has no landmark '{}' (measurements need the landmarks of the "
                                   "generated model or of an SMPL-format model){}",
                                   model.name, name, model.labels_note.empty() ? "" : ": " + model.labels_note));
  return it->second;
}

int joint(const BodyModel& model, const char* name) {
  const int j = model.joint_index(name);
  if (j < 0) throw InvalidInput(fmt::format("body model '{}' has no joint '{}' (needed by the measurements)", model.name, name));
  return j;
}

}  // namespace

const MeasurementInfo& measurement_info(Measurement m) { return kInfo[static_cast<size_t>(m)]; }

Measurement measurement_from_key(const std::string& key) {
  for (int i = 0; i < kNumMeasurements; ++i)
    if (key == kInfo[static_cast<size_t>(i)].key) return static_cast<Measurement>(i);
  std::string all;
  for (const auto& info : kInfo) all += (all.empty() ? "" : ", ") + std::string(info.key);
  throw InvalidInput(fmt::format("unknown measurement '{}'; the measurements are: {}", key, all));
}

double section_girth(const TriMesh& mesh, const Vec3& plane_point, const Vec3& normal, const Vec3& axis_point) {
  const Vec3 n = normal.normalized();
  const Vec3 e1 = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 e2 = n.cross(e1);
  std::vector<double> s(mesh.vertices.size());
  for (size_t i = 0; i < s.size(); ++i) {
    s[i] = n.dot(mesh.vertices[i] - plane_point);
    if (s[i] == 0.0) s[i] = 1e-12;  // on the plane counts as above
  }
  // Crossing points keyed by their mesh edge; loops = components of the
  // segments (crossings of one face are joined).
  std::unordered_map<uint64_t, int> id;
  std::vector<Vec2> pts;
  std::vector<std::array<int, 2>> segs;
  const uint64_t nv = mesh.vertices.size();
  auto crossing = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    const uint64_t key = static_cast<uint64_t>(a) * nv + static_cast<uint64_t>(b);
    auto [it, fresh] = id.try_emplace(key, static_cast<int>(pts.size()));
    if (fresh) {
      const double t = s[static_cast<size_t>(a)] / (s[static_cast<size_t>(a)] - s[static_cast<size_t>(b)]);
      const Vec3 p = mesh.vertices[static_cast<size_t>(a)] +
                     t * (mesh.vertices[static_cast<size_t>(b)] - mesh.vertices[static_cast<size_t>(a)]) - plane_point;
      pts.emplace_back(p.dot(e1), p.dot(e2));
    }
    return it->second;
  };
  for (const auto& f : mesh.faces) {
    int c[2], nc = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = f[static_cast<size_t>(k)], b = f[static_cast<size_t>((k + 1) % 3)];
      if ((s[static_cast<size_t>(a)] < 0.0) != (s[static_cast<size_t>(b)] < 0.0) && nc < 2) c[nc++] = crossing(a, b);
    }
    if (nc == 2) segs.push_back({c[0], c[1]});
  }
  if (pts.empty()) throw InvalidInput("section_girth: the plane does not cut the body");
  UnionFind uf(pts.size());
  for (const auto& sg : segs) uf.unite(sg[0], sg[1]);
  std::unordered_map<int, std::vector<Vec2>> loops;
  for (size_t i = 0; i < pts.size(); ++i) loops[uf.find(static_cast<int>(i))].push_back(pts[i]);
  const Vec3 qa = axis_point - plane_point;
  const Vec2 q(qa.dot(e1), qa.dot(e2));
  double best_inside = 1e300, best_outside = 1e300, best_outside_dist = 1e300;
  // Deterministic order: by representative.
  std::vector<int> reps;
  for (const auto& [r, v] : loops) reps.push_back(r);
  std::sort(reps.begin(), reps.end());
  for (int r : reps) {
    const auto hull = convex_hull(loops[r]);
    const double per = perimeter(hull);
    const double d = hull_outside_distance(hull, q);
    if (d <= 0.0) {
      best_inside = std::min(best_inside, per);
    } else if (d < best_outside_dist) {
      best_outside_dist = d;
      best_outside = per;
    }
  }
  return best_inside < 1e300 ? best_inside : best_outside;
}

BodyMeasurements measure_body(const BodyModel& model, const ShapedBody& shaped) {
  const auto& v = shaped.vertices;
  const auto& J = shaped.joints;
  auto P = [&](const char* name) { return v[static_cast<size_t>(landmark(model, name))]; };
  auto Jt = [&](const char* name) { return J[static_cast<size_t>(joint(model, name))]; };
  double zmin = 1e300, zmax = -1e300;
  for (const auto& p : v) {
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
  }
  const TriMesh mesh{v, model.faces};
  BodyMeasurements m{};
  auto set = [&](Measurement k, double value) { m[static_cast<size_t>(k)] = value; };
  set(Measurement::Stature, zmax - zmin);
  set(Measurement::InsideLegLength, P("crotch").z() - zmin);
  set(Measurement::ArmLength, (P("left_acromion") - P("left_elbow")).norm() + (P("left_elbow") - P("left_wrist")).norm());
  set(Measurement::ShoulderWidth, (P("left_acromion") - P("right_acromion")).norm());
  auto horizontal = [&](const char* lm, const char* axis_joint) {
    const Vec3 p = P(lm);
    const Vec3 a = Jt(axis_joint);
    return section_girth(mesh, p, Vec3::UnitZ(), Vec3(a.x(), a.y(), p.z()));
  };
  set(Measurement::ChestGirth, horizontal("chest", "spine2"));
  set(Measurement::WaistGirth, horizontal("waist", "spine1"));
  set(Measurement::HipGirth, horizontal("hip", "pelvis"));
  set(Measurement::NeckGirth, horizontal("neck", "neck"));
  set(Measurement::HeadGirth, horizontal("head", "head"));
  auto limb = [&](const char* lm, const char* from, const char* to) {
    const Vec3 a = Jt(from), b = Jt(to), p = P(lm);
    const Vec3 n = (b - a).normalized();
    const Vec3 q = a + n * n.dot(p - a);
    return section_girth(mesh, p, n, q);
  };
  set(Measurement::UpperArmGirth, limb("left_upper_arm", "left_shoulder", "left_elbow"));
  set(Measurement::ThighGirth, limb("left_thigh", "left_hip", "left_knee"));
  set(Measurement::CalfGirth, limb("left_calf", "left_knee", "left_ankle"));
  return m;
}

ShapeFromMeasurements shape_from_measurements(const BodyModel& model, const MeasurementTargets& targets) {
  // Map measurements to shape parameters by name.
  std::array<int, kNumMeasurements> param{};
  for (int k = 0; k < kNumMeasurements; ++k) {
    const auto it = std::find(model.shape_names.begin(), model.shape_names.end(), kInfo[static_cast<size_t>(k)].key);
    if (it == model.shape_names.end())
      throw InvalidInput(fmt::format("body model '{}' has no shape parameter '{}': only a model whose shape "
                                     "parameters are the measurements (the generated one) can be driven by them",
                                     model.name, kInfo[static_cast<size_t>(k)].key));
    param[static_cast<size_t>(k)] = static_cast<int>(it - model.shape_names.begin());
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.num_shapes());
  const BodyMeasurements base = measure_body(model, shape_body(model, zero));
  ShapeFromMeasurements out;
  const double stature = targets.mm[0] ? *targets.mm[0] : base[0];
  for (int k = 0; k < kNumMeasurements; ++k) {
    const auto sk = static_cast<size_t>(k);
    if (targets.mm[sk]) {
      const double t = *targets.mm[sk];
      if (!(t > 0.0) || !std::isfinite(t))
        throw InvalidInput(fmt::format("{}: {} mm is not a positive length", kInfo[sk].iso_term, t));
      if (t < 0.5 * base[sk] || t > 1.6 * base[sk])
        throw InvalidInput(fmt::format("{}: {:.0f} mm is outside what the body model represents faithfully "
                                       "({:.0f}-{:.0f} mm, half to 1.6 times the template's {:.0f} mm)",
                                       kInfo[sk].iso_term, t, 0.5 * base[sk], 1.6 * base[sk], base[sk]));
      out.targets[sk] = t;
    } else {
      out.targets[sk] = kInfo[sk].is_girth || k == 0 ? base[sk] : base[sk] * stature / base[0];
    }
  }
  Eigen::VectorXd shape = zero;
  auto residual = [&](const Eigen::VectorXd& s, BodyMeasurements* got) {
    const BodyMeasurements m = measure_body(model, shape_body(model, s));
    if (got) *got = m;
    Eigen::VectorXd r(kNumMeasurements);
    for (int k = 0; k < kNumMeasurements; ++k) r(k) = m[static_cast<size_t>(k)] - out.targets[static_cast<size_t>(k)];
    return r;
  };
  Eigen::VectorXd r = residual(shape, &out.achieved);
  for (out.iterations = 0; out.iterations < 12 && r.cwiseAbs().maxCoeff() > 0.05; ++out.iterations) {
    Eigen::MatrixXd jac(kNumMeasurements, kNumMeasurements);
    for (int k = 0; k < kNumMeasurements; ++k) {
      Eigen::VectorXd sp = shape, sm = shape;
      sp(param[static_cast<size_t>(k)]) += 1.0;
      sm(param[static_cast<size_t>(k)]) -= 1.0;
      jac.col(k) = 0.5 * (residual(sp, nullptr) - residual(sm, nullptr));
    }
    const Eigen::VectorXd step = jac.fullPivLu().solve(-r);
    // Backtrack so that the residual decreases.
    double t = 1.0;
    Eigen::VectorXd best_shape = shape;
    Eigen::VectorXd best_r = r;
    for (int ls = 0; ls < 6; ++ls, t *= 0.5) {
      Eigen::VectorXd trial = shape;
      for (int k = 0; k < kNumMeasurements; ++k) trial(param[static_cast<size_t>(k)]) += t * step(k);
      const Eigen::VectorXd rt = residual(trial, nullptr);
      if (rt.norm() < best_r.norm()) {
        best_shape = trial;
        best_r = rt;
        break;
      }
    }
    if (best_r.norm() >= r.norm()) break;
    shape = best_shape;
    r = best_r;
  }
  r = residual(shape, &out.achieved);
  out.shape = shape;
  out.max_error_mm = r.cwiseAbs().maxCoeff();
  if (out.max_error_mm > 0.5)
    throw SolverError(fmt::format("shape_from_measurements: the measurements could not be met (largest error "
                                  "{:.1f} mm after {} iterations); the combination may be outside the model's range",
                                  out.max_error_mm, out.iterations));
  return out;
}

}  // namespace knitforge
