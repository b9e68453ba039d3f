#include "knitforge/geometry/cotan_laplacian.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kMaxCot = 1e6;

void check_faces(const TriMesh& mesh, const char* what) {
  const int n = mesh.num_vertices();
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k];
      if (v < 0 || v >= n) {
        throw InvalidInput(fmt::format("{}: face {} uses vertex {}, outside [0, {})", what, f, v, n));
      }
    }
  }
}

/// Cotangent of the angle at a between a->b and a->c, clamped.
double cot_at(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, w = c - a;
  const double cross = u.cross(w).norm();
  const double dot = u.dot(w);
  if (!(cross > 0.0)) return dot >= 0.0 ? kMaxCot : -kMaxCot;
  return std::clamp(dot / cross, -kMaxCot, kMaxCot);
}

}  // namespace

SparseMatrix cotan_laplacian(const TriMesh& mesh) {
  check_faces(mesh, "cotangent Laplacian");
  const int n = mesh.num_vertices();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(mesh.num_faces()) * 9 + static_cast<size_t>(n));
  for (int v = 0; v < n; ++v) t.emplace_back(v, v, 0.0);
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const int i = f[k], j = f[(k + 1) % 3], o = f[(k + 2) % 3];
      const double w = 0.5 * cot_at(mesh.vertices[o], mesh.vertices[i], mesh.vertices[j]);
      t.emplace_back(i, j, -w);
      t.emplace_back(j, i, -w);
      t.emplace_back(i, i, w);
      t.emplace_back(j, j, w);
    }
  }
  SparseMatrix L(n, n);
  L.setFromTriplets(t.begin(), t.end());
  L.makeCompressed();
  return L;
}

std::vector<double> mixed_voronoi_areas(const TriMesh& mesh) {
  check_faces(mesh, "Voronoi areas");
  std::vector<double> area(static_cast<size_t>(mesh.num_vertices()), 0.0);
  for (const auto& f : mesh.faces) {
    const Vec3& p0 = mesh.vertices[f[0]];
    const Vec3& p1 = mesh.vertices[f[1]];
    const Vec3& p2 = mesh.vertices[f[2]];
    const double A = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    if (!(A > 0.0)) continue;
    const std::array<const Vec3*, 3> p{&p0, &p1, &p2};
    int obtuse = -1;
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = *p[k];
      if ((*p[(k + 1) % 3] - a).dot(*p[(k + 2) % 3] - a) < 0.0) obtuse = k;
    }
    if (obtuse >= 0) {
      for (int k = 0; k < 3; ++k) area[f[k]] += k == obtuse ? 0.5 * A : 0.25 * A;
      continue;
    }
    // Voronoi part of corner k: (|e_k,k+1|^2 cot(angle at k+2) + |e_k,k+2|^2 cot(angle at k+1)) / 8.
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = *p[k];
      const Vec3& b = *p[(k + 1) % 3];
      const Vec3& c = *p[(k + 2) % 3];
      const double cot_c = cot_at(c, a, b), cot_b = cot_at(b, c, a);
      area[f[k]] += ((b - a).squaredNorm() * cot_c + (c - a).squaredNorm() * cot_b) / 8.0;
    }
  }
  return area;
}

SparseMatrix voronoi_mass_matrix(const TriMesh& mesh) {
  const std::vector<double> a = mixed_voronoi_areas(mesh);
  SparseMatrix M(mesh.num_vertices(), mesh.num_vertices());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(a.size());
  for (size_t v = 0; v < a.size(); ++v) t.emplace_back(static_cast<int>(v), static_cast<int>(v), a[v]);
  M.setFromTriplets(t.begin(), t.end());
  return M;
}

}  // namespace knitforge
