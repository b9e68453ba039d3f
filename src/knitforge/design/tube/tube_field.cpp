#include "knitforge/design/tube/tube_field.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/cotan_laplacian.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

double loop_length(const TriMesh& mesh, const std::vector<int>& loop) {
  double len = 0.0;
  for (size_t i = 0; i < loop.size(); ++i)
    len += (mesh.vertices[loop[(i + 1) % loop.size()]] - mesh.vertices[loop[i]]).norm();
  return len;
}

}  // namespace

TubeField tube_field(const TriMesh& mesh, const std::string& what) {
  const SurfaceReport rep = validate_surface(mesh);
  if (!rep.manifold || rep.num_components != 1) {
    throw InvalidInput(fmt::format(
        "{}: --tube needs one piece of manifold, consistently oriented surface with two boundary loops; this "
        "one is not ({}); repair it or design it without --tube",
        what, rep.manifold ? fmt::format("{} pieces", rep.num_components) : std::string("not manifold")));
  }
  if (rep.num_boundary_loops != 2 || rep.genus != 0) {
    throw InvalidInput(fmt::format(
        "{}: --tube needs a surface with two boundary loops (a tube: sleeve, leg, body) or one (a closed "
        "tube: a beanie) and no handle, this one has {} boundary loop(s) and genus {}; design it without "
        "--tube, as a sheet (more "
        "loops or handles are then cut open by seams first)",
        what, rep.num_boundary_loops, rep.genus));
  }
  const Halfedges he = build_halfedges(mesh.num_vertices(), mesh.faces);
  std::vector<std::vector<int>> loops = he.boundary_loops();
  TubeField f;
  const double l0 = loop_length(mesh, loops[0]), l1 = loop_length(mesh, loops[1]);
  const int start = l1 > l0 ? 1 : 0;
  f.start_loop = loops[static_cast<size_t>(start)];
  f.end_loop = loops[static_cast<size_t>(1 - start)];
  f.start_length = start == 0 ? l0 : l1;
  f.end_length = start == 0 ? l1 : l0;

  return field_with_level_rims(mesh, cotan_laplacian(mesh), std::move(f));
}

TubeField field_with_level_rims(const TriMesh& mesh, const SparseMatrix& K, TubeField rims) {
  // Dirichlet u = 0 / 1 on the rims; the rest solved from K_FF u_F = -K_FB u_B.
  const int n = mesh.num_vertices();
  if (K.rows() != n || K.cols() != n)
    throw InvalidInput(fmt::format("tube field: a stiffness of {} x {} for {} vertices", K.rows(), K.cols(), n));
  TubeField f = std::move(rims);
  std::vector<double> fixed(static_cast<size_t>(n), -1.0);
  for (int v : f.start_loop) fixed[static_cast<size_t>(v)] = 0.0;
  for (int v : f.end_loop) fixed[static_cast<size_t>(v)] = 1.0;
  std::vector<int> index(static_cast<size_t>(n), -1);
  int free = 0;
  for (int v = 0; v < n; ++v)
    if (fixed[static_cast<size_t>(v)] < 0) index[static_cast<size_t>(v)] = free++;
  f.value.assign(static_cast<size_t>(n), 0.0);
  for (int v = 0; v < n; ++v)
    if (fixed[static_cast<size_t>(v)] >= 0) f.value[static_cast<size_t>(v)] = fixed[static_cast<size_t>(v)];
  if (free == 0) return f;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(free);
  for (int col = 0; col < K.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(K, col); it; ++it) {
      const int r = static_cast<int>(it.row()), c = static_cast<int>(it.col());
      const int ir = index[static_cast<size_t>(r)];
      if (ir < 0) continue;
      const int ic = index[static_cast<size_t>(c)];
      if (ic >= 0) {
        trip.emplace_back(ir, ic, it.value());
      } else {
        rhs[ir] -= it.value() * fixed[static_cast<size_t>(c)];
      }
    }
  }
  SparseMatrix A(free, free);
  A.setFromTriplets(trip.begin(), trip.end());
  const Eigen::VectorXd x = solve_spd(A, rhs);
  for (int v = 0; v < n; ++v) {
    const int i = index[static_cast<size_t>(v)];
    if (i >= 0) f.value[static_cast<size_t>(v)] = std::clamp(x[i], 0.0, 1.0);
  }
  f.interior_extrema = count_interior_extrema(mesh, f.value);
  return f;
}

RoundLevels round_levels(const TriMesh& mesh, const TubeField& field, double stitch_height) {
  if (!(stitch_height > 0.0) || !std::isfinite(stitch_height))
    throw InvalidInput(fmt::format("tube rounds: the stitch height must be positive, got {}", stitch_height));
  constexpr int kTable = 512;
  std::vector<double> mid(kTable);
  for (int j = 0; j < kTable; ++j) mid[static_cast<size_t>(j)] = (j + 0.5) / kTable;
  const std::vector<Vec3> grad = field_face_gradients(mesh, field.value);
  const auto curves = extract_isocurves(mesh, field.value, mid);
  // D at the table's knots j / kTable.
  std::vector<double> D(kTable + 1, 0.0);
  for (int j = 0; j < kTable; ++j) {
    double len = 0.0, inv = 0.0;
    for (const Isocurve& c : curves[static_cast<size_t>(j)]) {
      const int segs = static_cast<int>(c.faces.size());
      for (int s = 0; s < segs; ++s) {
        const double l = (c.positions[static_cast<size_t>((s + 1) % c.num_points())] - c.positions[static_cast<size_t>(s)]).norm();
        const double g = grad[static_cast<size_t>(c.faces[static_cast<size_t>(s)])].norm();
        len += l;
        if (g > 0.0) inv += l / g;
      }
    }
    if (curves[static_cast<size_t>(j)].size() != 1 || !curves[static_cast<size_t>(j)][0].closed || !(len > 0.0)) {
      throw InvalidInput(fmt::format(
          "tube rounds: the level u = {:.4f} of the tube field is {} pieces{}, not one closed round; the surface "
          "is not a tube this route can knit in the round (design it without --tube)",
          mid[static_cast<size_t>(j)], curves[static_cast<size_t>(j)].size(),
          curves[static_cast<size_t>(j)].size() == 1 ? " (open)" : ""));
    }
    D[static_cast<size_t>(j + 1)] = D[static_cast<size_t>(j)] + inv / len / kTable;
  }
  RoundLevels r;
  r.mean_length = D[kTable];
  const int K = std::max(1, static_cast<int>(std::lround(r.mean_length / stitch_height)));
  r.levels.resize(static_cast<size_t>(K) + 1);
  r.levels.front() = 0.0;
  r.levels.back() = 1.0;
  int j = 0;
  for (int k = 1; k < K; ++k) {
    const double target = r.mean_length * k / K;
    while (j + 1 < kTable && D[static_cast<size_t>(j + 1)] < target) ++j;
    const double d0 = D[static_cast<size_t>(j)], d1 = D[static_cast<size_t>(j + 1)];
    const double t = d1 > d0 ? (target - d0) / (d1 - d0) : 0.5;
    r.levels[static_cast<size_t>(k)] = (j + std::clamp(t, 0.0, 1.0)) / kTable;
  }
  return r;
}

}  // namespace knitforge
