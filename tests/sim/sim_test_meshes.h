#pragma once
// Small stitch meshes and helpers shared by the simulator tests.

#include <vector>

#include <Eigen/Core>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
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

// A proper rotation from an axis-angle.
inline Mat3 rotation(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

}  // namespace knitforge::test
