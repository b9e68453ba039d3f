#pragma once
// Small stitch meshes and helpers shared by the simulator tests.

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/sim/knit_material.h"
#include "knitforge/sim/sim_model.h"
#include "knitforge/sim/sim_state.h"
#include "knitforge/geometry/vec.h"

namespace knitforge::test {

// Square stitches of s x s mm.
inline KnitParams square_stitches(double s) {
  KnitParams p;
  p.stitch_width = s;
  p.stitch_height = s;
  return p;
}

// At rest at positions x (zero velocity, t = 0).
inline SimState at_rest(const Eigen::VectorXd& x) { return {x, Eigen::VectorXd::Zero(x.size()), 0.0}; }

// A flat sheet of cols x rows Knit stitches of w x h mm in z = 0, courses
// along x; vertex (i, j) (column i = 0..cols, row j = 0..rows) has index
// j (cols + 1) + i.
inline StitchMesh knit_sheet(int cols, int rows, double w, double h) {
  StitchMesh m;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) m.vertices.emplace_back(w * i, h * j, 0.0);
  auto id = [cols](int i, int j) { return j * (cols + 1) + i; };
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      Stitch s;
      s.type = StitchType::Knit;
      s.v = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      s.course = j;
      s.wale = i;
      m.stitches.push_back(s);
    }
  }
  return m;
}

inline Eigen::VectorXd flatten(const std::vector<Vec3>& p) {
  Eigen::VectorXd x(3 * p.size());
  for (size_t i = 0; i < p.size(); ++i) x.segment<3>(3 * i) = p[i];
  return x;
}

inline std::vector<Vec3> unflatten(const Eigen::VectorXd& x) {
  std::vector<Vec3> p(x.size() / 3);
  for (size_t i = 0; i < p.size(); ++i) p[i] = x.segment<3>(3 * i);
  return p;
}

// A strip `length` x `width` mm of square stitches of `spacing_mm` (vertex
// (i, j) as knit_sheet()), of a nearly inextensible knit (tension stiffness
// 2e4 N/m along courses and wales, shear 5e3 N/m) with bending rigidity
// `bending_un_m` (µN m) both ways, clamped at x = 0: its first two columns
// of vertices pinned.
struct ClampedStrip {
  SimModel model;
  int cols = 0, rows = 0;
  // The mean height (z) of the free end's column of vertices at x (3n).
  double tip_height_mm(const Eigen::VectorXd& x) const {
    double tip = 0.0;
    for (int j = 0; j <= rows; ++j) tip += x[3 * (j * (cols + 1) + cols) + 2];
    return tip / (rows + 1);
  }
};
inline ClampedStrip clamped_strip(double spacing_mm, double bending_un_m, double length = 20.0, double width = 4.0) {
  ClampedStrip s;
  s.cols = static_cast<int>(std::lround(length / spacing_mm)) + 1;  // one column clamped
  s.rows = static_cast<int>(std::lround(width / spacing_mm));
  KnitMaterial m = default_single_jersey();
  m.course = TensionCurve{{{0.0, 2e4}}, 2e4};
  m.wale = TensionCurve{{{0.0, 2e4}}, 2e4};
  m.shear = TensionCurve{{{0.0, 5e3}}, 5e3};
  m.bending_course_un_m = bending_un_m;
  m.bending_wale_un_m = bending_un_m;
  SimModelOptions mo;
  mo.materials = {m};
  s.model = build_sim_model(knit_sheet(s.cols, s.rows, spacing_mm, spacing_mm), square_stitches(spacing_mm), mo);
  for (int j = 0; j <= s.rows; ++j) {
    s.model.pinned.push_back(j * (s.cols + 1));
    s.model.pinned.push_back(j * (s.cols + 1) + 1);
  }
  std::sort(s.model.pinned.begin(), s.model.pinned.end());
  return s;
}

// Positions x (3n) of the model's rest positions scaled by `scale` plus
// uniform noise in [-noise, noise] per coordinate (seeded).
inline Eigen::VectorXd perturbed(const SimModel& model, unsigned seed, double scale, double noise) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise, noise);
  Eigen::VectorXd x = flatten(model.rest_positions);
  for (Eigen::Index k = 0; k < x.size(); ++k) x[k] = x[k] * scale + u(rng);
  return x;
}

// A proper rotation from an axis-angle.
inline Mat3 rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

}  // namespace knitforge::test
