#include "knitforge/geometry/tutte_embedding.h"

#include <cmath>
#include <numbers>
#include <string>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/util/errors.h"

namespace knitforge {

TutteEmbedding tutte_embedding(const TriMesh& mesh) {
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  int num_components = 0;
  he.face_components(&num_components);
  if (num_components != 1) {
    throw TopologyError("tutte_embedding: the mesh has " + std::to_string(num_components) +
                        " connected components; flatten each component separately");
  }
  const auto loops = he.boundary_loops();
  if (loops.empty()) {
    throw TopologyError(
        "tutte_embedding: the mesh is closed (no boundary); cut it open into a disk first "
        "(e.g. along a seam from one point to another)");
  }
  auto loop_length = [&](const std::vector<int>& loop) {
    double len = 0.0;
    for (size_t i = 0; i < loop.size(); ++i) {
      len += (mesh.vertices[loop[(i + 1) % loop.size()]] - mesh.vertices[loop[i]]).norm();
    }
    return len;
  };
  size_t best = 0;
  double best_len = -1.0;
  for (size_t i = 0; i < loops.size(); ++i) {
    const double len = loop_length(loops[i]);
    if (len > best_len + 1e-12 * std::abs(best_len)) {
      best_len = len;
      best = i;
    }
  }
  if (!(best_len > 0.0)) throw InvalidInput("tutte_embedding: the boundary loop has zero length");

  TutteEmbedding out;
  out.outer_loop = loops[best];
  out.radius = best_len / (2.0 * std::numbers::pi);
  const int n = mesh.num_vertices();
  out.uv.assign(n, Vec2::Zero());
  std::vector<int> unknown(n, -1);
  std::vector<char> fixed(n, 0);
  double acc = 0.0;
  const auto& loop = out.outer_loop;
  for (size_t i = 0; i < loop.size(); ++i) {
    const double angle = 2.0 * std::numbers::pi * acc / best_len;
    out.uv[loop[i]] = out.radius * Vec2(std::cos(angle), std::sin(angle));
    fixed[loop[i]] = 1;
    acc += (mesh.vertices[loop[(i + 1) % loop.size()]] - mesh.vertices[loop[i]]).norm();
  }
  int m = 0;
  for (int v = 0; v < n; ++v) {
    if (!fixed[v] && !he.is_isolated_vertex(v)) unknown[v] = m++;
  }
  if (m == 0) return out;

  // Uniform graph Laplacian over the undirected edges (each interior edge
  // appears as two half-edges, a boundary edge as one).
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(he.num_halfedges()) * 2);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 2);
  for (int h = 0; h < he.num_halfedges(); ++h) {
    const int o = he.opposite(h);
    if (o >= 0 && o < h) continue;  // each edge once
    const int a = he.from(h);
    const int b = he.to(h);
    for (int k = 0; k < 2; ++k) {
      const int i = k == 0 ? a : b;
      const int j = k == 0 ? b : a;
      if (unknown[i] < 0) continue;
      trip.emplace_back(unknown[i], unknown[i], 1.0);
      if (unknown[j] >= 0) {
        trip.emplace_back(unknown[i], unknown[j], -1.0);
      } else {
        rhs.row(unknown[i]) += out.uv[j].transpose();
      }
    }
  }
  SparseMatrix L(m, m);
  L.setFromTriplets(trip.begin(), trip.end());
  SparseSolver solver(L);
  const Eigen::MatrixXd x = solver.solve_columns(rhs);
  for (int v = 0; v < n; ++v) {
    if (unknown[v] >= 0) out.uv[v] = x.row(unknown[v]).transpose();
  }
  return out;
}

}  // namespace knitforge
