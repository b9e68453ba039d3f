#pragma once
// A tiny synthetic body model for the body tests: a closed tube around a
// chain of three joints along +x (root at the origin, then x = 40, x = 80),
// rings of 8 vertices every 10 mm, caps at both ends; skinning weights blend
// neighbouring joints; two shape blend shapes and (optionally) pose-corrective
// blend shapes with arbitrary deterministic values.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "knitforge/body/body_model.h"

namespace knitforge::test {

inline BodyModel tube_body_model(bool with_pose_basis) {
  BodyModel m;
  m.name = "test-tube";
  const int rings = 11, per = 8;  // x = 0, 10, ..., 100
  const double radius = 12.0;
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < per; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / per;
      m.template_vertices.emplace_back(10.0 * r, radius * std::cos(phi), radius * std::sin(phi));
    }
  }
  const int cap0 = static_cast<int>(m.template_vertices.size());
  m.template_vertices.emplace_back(-8.0, 0.0, 0.0);
  const int cap1 = cap0 + 1;
  m.template_vertices.emplace_back(108.0, 0.0, 0.0);
  auto id = [&](int r, int s) { return r * per + (s % per); };
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < per; ++s) {
      m.faces.push_back({id(r, s), id(r + 1, s), id(r + 1, s + 1)});
      m.faces.push_back({id(r, s), id(r + 1, s + 1), id(r, s + 1)});
    }
  }
  for (int s = 0; s < per; ++s) {
    m.faces.push_back({cap0, id(0, s), id(0, s + 1)});
    m.faces.push_back({cap1, id(rings - 1, s + 1), id(rings - 1, s)});
  }
  const int V = static_cast<int>(m.template_vertices.size());
  m.parents = {-1, 0, 1};
  m.joint_names = {"root", "middle", "tip"};
  const double joint_x[3] = {0.0, 40.0, 80.0};
  // Skinning: piecewise-linear hat functions of x over the joints.
  std::vector<Eigen::Triplet<double>> w;
  for (int i = 0; i < V; ++i) {
    const double x = std::clamp(m.template_vertices[static_cast<size_t>(i)].x(), 0.0, 80.0);
    const int j = x >= 40.0 ? 1 : 0;
    const double t = (x - joint_x[j]) / 40.0;
    if (1.0 - t > 0.0) w.emplace_back(i, j, 1.0 - t);
    if (t > 0.0) w.emplace_back(i, j + 1, t);
  }
  m.skinning_weights.resize(V, 3);
  m.skinning_weights.setFromTriplets(w.begin(), w.end());
  // Regressor: each joint is the mean of its ring (x = 0, 40, 80).
  std::vector<Eigen::Triplet<double>> rg;
  for (int j = 0; j < 3; ++j)
    for (int s = 0; s < per; ++s) rg.emplace_back(j, id(4 * j, s), 1.0 / per);
  m.joint_regressor.resize(3, V);
  m.joint_regressor.setFromTriplets(rg.begin(), rg.end());
  // Shapes: 0 stretches along x, 1 inflates the radius, both with a twist of
  // arbitrary values so that no derivative term vanishes by symmetry.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  m.shape_basis.resize(3 * V, 2);
  for (int i = 0; i < V; ++i) {
    const Vec3& p = m.template_vertices[static_cast<size_t>(i)];
    m.shape_basis.block<3, 1>(3 * i, 0) = Vec3(0.1 * p.x() + u(rng), u(rng), u(rng));
    m.shape_basis.block<3, 1>(3 * i, 1) = Vec3(u(rng), 0.1 * p.y() + u(rng), 0.1 * p.z() + u(rng));
  }
  m.shape_names = {"stretch", "inflate"};
  if (with_pose_basis) {
    m.pose_basis.resize(3 * V, 9 * 2);
    for (int r = 0; r < m.pose_basis.rows(); ++r)
      for (int c = 0; c < m.pose_basis.cols(); ++c) m.pose_basis(r, c) = 5.0 * u(rng);
  }
  return m;
}

}  // namespace knitforge::test
