#include "knitforge/geometry/slim_flatten.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/core.h>
#include <Eigen/SVD>

#include "knitforge/geometry/arap_flatten.h"
#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/union_find.h"

namespace knitforge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Conjugate gradients on A x = b (A symmetric positive definite, its lower
// triangle stored) from the given x, preconditioned by the factor M of a
// nearby matrix. Each step lowers the quadratic ½xᵀAx − bᵀx, so every iterate
// is a descent direction for SLIM (the proxy's gradient at the current map is
// the energy's): the solve need only be inexact, as in inexact Newton
// methods. True when the residual falls to `forcing` times the starting one
// (or to 1e-8 |b|) within kMaxSteps steps; x is then the approximate solution.
bool preconditioned_cg(const SparseMatrix& A, const Eigen::VectorXd& b, const SparseSolver& M, double forcing,
                       Eigen::VectorXd& x) {
  constexpr int kMaxSteps = 6;
  const auto S = A.selfadjointView<Eigen::Lower>();
  Eigen::VectorXd r = b - S * x;
  const double goal = std::max(1e-8 * b.norm(), forcing * r.norm());
  if (r.norm() <= 1e-8 * b.norm()) return true;
  Eigen::VectorXd z = M.solve(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  for (int k = 0; k < kMaxSteps; ++k) {
    const Eigen::VectorXd Ap = S * p;
    const double pAp = p.dot(Ap);
    if (!(pAp > 0.0)) return false;
    const double alpha = rz / pAp;
    x += alpha * p;
    r -= alpha * Ap;
    if (r.norm() <= goal) return true;
    z = M.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

// The proxy's matrix has one pattern for all iterations: its lower triangle
// is built once, and slot[36 f + 6 a + c] is the position in A.valuePtr() to
// which entry (a, c) of face f's 6 x 6 block adds (-1 where it adds nothing:
// a fixed unknown, the upper triangle, or a face without area). Assembling
// into the slots costs a fraction of building the matrix from triplets every
// iteration.
struct ProxyPattern {
  SparseMatrix A;
  std::vector<int> slot;
};

// ids(f, out) writes face f's 6 unknowns (-1: fixed); skip(f): f adds nothing.
template <class FaceUnknowns, class SkipFace>
ProxyPattern proxy_pattern(int num_unknowns, int num_faces, FaceUnknowns&& ids_of, SkipFace&& skip) {
  ProxyPattern pat;
  std::vector<Eigen::Triplet<double>> trip;
  for (int f = 0; f < num_faces; ++f) {
    if (skip(f)) continue;
    int ids[6];
    ids_of(f, ids);
    for (int a = 0; a < 6; ++a) {
      for (int c = 0; c < 6; ++c) {
        if (ids[a] >= 0 && ids[c] >= 0 && ids[c] <= ids[a]) trip.emplace_back(ids[a], ids[c], 0.0);
      }
    }
  }
  pat.A.resize(num_unknowns, num_unknowns);
  pat.A.setFromTriplets(trip.begin(), trip.end());
  pat.A.makeCompressed();
  const int* outer = pat.A.outerIndexPtr();
  const int* inner = pat.A.innerIndexPtr();
  pat.slot.assign(static_cast<size_t>(num_faces) * 36, -1);
  for (int f = 0; f < num_faces; ++f) {
    if (skip(f)) continue;
    int ids[6];
    ids_of(f, ids);
    for (int a = 0; a < 6; ++a) {
      for (int c = 0; c < 6; ++c) {
        if (ids[a] < 0 || ids[c] < 0 || ids[c] > ids[a]) continue;
        const int* begin = inner + outer[ids[c]];
        const int* end = inner + outer[ids[c] + 1];
        pat.slot[static_cast<size_t>(f) * 36 + 6 * a + c] = static_cast<int>(std::lower_bound(begin, end, ids[a]) - inner);
      }
    }
  }
  return pat;
}

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Per face: 3D area and the gradients g_j of the linear basis functions in
// the isometric frame, so that J = Σ_j u_j g_jᵀ.
struct FaceOperator {
  double area = 0.0;
  std::array<Vec2, 3> g{};
};

// One unknown per coordinate group (vertices joined by constraints); -1 for
// the group of the pinned vertex (kept where it is: translation) and for
// unused vertices.
struct Unknowns {
  std::vector<int> index[2];
  int count[2] = {0, 0};
  std::vector<std::vector<int>> groups[2];  // members of each constrained group (size >= 2)
};

Unknowns number_unknowns(int n, const std::vector<char>& used, int pinned,
                         const std::vector<std::pair<int, int>>* const* pairs) {
  Unknowns u;
  for (int d = 0; d < 2; ++d) {
    UnionFind uf(static_cast<size_t>(n));
    for (const auto& [a, b] : *pairs[d]) uf.unite(a, b);
    const int pinned_root = uf.find(pinned);
    std::vector<int> root_index(n, -1);
    std::vector<int> root_group(n, -1);
    u.index[d].assign(n, -1);
    for (int v = 0; v < n; ++v) {
      if (!used[v]) continue;
      const int r = uf.find(v);
      if (r != pinned_root) {
        if (root_index[r] < 0) root_index[r] = u.count[d]++;
        u.index[d][v] = root_index[r];
      }
    }
    for (const auto& [a, b] : *pairs[d]) {
      (void)b;
      const int r = uf.find(a);
      if (root_group[r] < 0) {
        root_group[r] = static_cast<int>(u.groups[d].size());
        u.groups[d].emplace_back();
      }
    }
    for (int v = 0; v < n; ++v) {
      const int r = uf.find(v);
      if (root_group[r] >= 0) u.groups[d][root_group[r]].push_back(v);
    }
  }
  return u;
}

double face_energy(const FaceOperator& op, const std::array<Vec2, 3>& q) {
  Mat2 J = Mat2::Zero();
  for (int j = 0; j < 3; ++j) J += q[j] * op.g[j].transpose();
  const double det = J.determinant();
  if (!(det > 0.0)) return kInf;
  return op.area * J.squaredNorm() * (1.0 + 1.0 / (det * det));
}

// Smallest t > 0 at which the signed area of the triangle (e1 + t d1, e2 + t d2) vanishes; +inf if none.
double first_degenerate_step(const Vec2& e1, const Vec2& e2, const Vec2& d1, const Vec2& d2) {
  const double c = cross2(e1, e2);
  const double b = cross2(e1, d2) + cross2(d1, e2);
  const double a = cross2(d1, d2);
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(c)});
  if (!(scale > 0.0)) return kInf;
  if (std::abs(a) <= 1e-14 * scale) return b < 0.0 ? -c / b : kInf;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return kInf;
  const double s = std::sqrt(disc);
  // Numerically stable roots.
  const double q = -0.5 * (b + (b >= 0.0 ? s : -s));
  double best = kInf;
  for (double t : {q / a, q != 0.0 ? c / q : kInf}) {
    if (t > 0.0 && t < best) best = t;
  }
  return best;
}

}  // namespace

SlimFlattenResult slim_flatten(const TriMesh& mesh, const SlimFlattenOptions& options) {
  const int n = mesh.num_vertices();
  const int nf = mesh.num_faces();
  if (nf == 0) throw InvalidInput("slim_flatten: the mesh has no faces");
  if (options.max_iterations < 0) throw InvalidInput("slim_flatten: max_iterations must be >= 0");
  if (!(options.tolerance >= 0.0)) throw InvalidInput("slim_flatten: tolerance must be >= 0");
  if (static_cast<int>(options.initial.size()) != n) {
    throw InvalidInput(
        fmt::format("slim_flatten: {} start positions for {} vertices", options.initial.size(), n));
  }
  std::vector<char> used(n, 0);
  for (const auto& t : mesh.faces) {
    for (int v : t) {
      if (v < 0 || v >= n) throw InvalidInput("slim_flatten: a face uses a vertex index out of range");
      used[v] = 1;
    }
  }
  for (const auto* pairs : {&options.equal_x, &options.equal_y}) {
    for (const auto& [a, b] : *pairs) {
      if (a < 0 || a >= n || b < 0 || b >= n)
        throw InvalidInput(
            fmt::format("slim_flatten: constraint ({}, {}) names a vertex out of range", a, b));
      if (!used[a] || !used[b])
        throw InvalidInput(fmt::format("slim_flatten: constraint ({}, {}) names an unused vertex", a, b));
    }
  }
  std::vector<Vec2> uv = options.initial;
  for (int v = 0; v < n; ++v) {
    if (used[v] && !uv[v].allFinite())
      throw InvalidInput(fmt::format("slim_flatten: start position of vertex {} is not finite", v));
  }
  for (int f = 0; f < nf; ++f) {
    if (!(signed_uv_area(mesh, uv, f) > 0.0)) {
      throw InvalidInput(fmt::format(
          "slim_flatten: face {} is flipped or degenerate in the start positions; the start must be "
          "injective",
          f));
    }
  }

  std::vector<FaceOperator> ops(nf);
  double total_area = 0.0;
  for (int f = 0; f < nf; ++f) {
    const auto x = isometric_triangle(mesh, f);
    const double l1 = x[1].x(), along = x[2].x(), up = x[2].y();
    ops[f].area = 0.5 * std::abs(l1 * up);
    total_area += ops[f].area;
    if (!(l1 > 0.0) || !(up > 0.0)) {
      ops[f].area = 0.0;
      continue;
    }
    // Rows of P⁻¹ for P = [x1 − x0, x2 − x0] = [[l1, along], [0, up]].
    const Vec2 g1(1.0 / l1, -along / (l1 * up));
    const Vec2 g2(0.0, 1.0 / up);
    ops[f].g = {-(g1 + g2), g1, g2};
  }
  if (!(total_area > 0.0)) throw InvalidInput("slim_flatten: the mesh has zero area");
  const double mean_area = total_area / nf;
  for (auto& op : ops) {
    if (op.area <= 1e-12 * mean_area) op.area = 0.0;
  }
  auto energy_of = [&](const std::vector<Vec2>& p) {
    double e = 0.0;
    for (int f = 0; f < nf; ++f) {
      if (ops[f].area == 0.0) continue;
      const auto& t = mesh.faces[f];
      e += face_energy(ops[f], {p[t[0]], p[t[1]], p[t[2]]});
      if (!std::isfinite(e)) return kInf;
    }
    return e / (4.0 * total_area);
  };

  // The pinned vertex: the used vertex closest to the centroid of the start.
  Vec2 centroid = Vec2::Zero();
  int count = 0;
  for (int v = 0; v < n; ++v) {
    if (used[v]) centroid += uv[v], ++count;
  }
  centroid /= std::max(count, 1);
  int pinned = -1;
  double best = kInf;
  for (int v = 0; v < n; ++v) {
    if (used[v] && (uv[v] - centroid).squaredNorm() < best)
      best = (uv[v] - centroid).squaredNorm(), pinned = v;
  }
  const std::vector<std::pair<int, int>>* pairs[2] = {&options.equal_x, &options.equal_y};
  const Unknowns unk = number_unknowns(n, used, pinned, pairs);
  const Vec2 fixed_value = uv[pinned];
  const int num_unknowns = unk.count[0] + unk.count[1];
  auto var = [&](int v, int d) {
    return unk.index[d][v] < 0 ? -1 : unk.index[d][v] + (d == 1 ? unk.count[0] : 0);
  };

  Vec2 lo = Vec2::Constant(kInf), hi = -lo;
  for (int v = 0; v < n; ++v) {
    if (used[v]) lo = lo.cwiseMin(uv[v]), hi = hi.cwiseMax(uv[v]);
  }
  const double size = (hi - lo).norm();
  auto residual_of = [&](const std::vector<Vec2>& p) {
    double r = 0.0;
    for (int d = 0; d < 2; ++d) {
      for (const auto& g : unk.groups[d]) {
        double a = kInf, b = -kInf;
        for (int v : g) a = std::min(a, p[v][d]), b = std::max(b, p[v][d]);
        // The pinned group must also reach the pinned value.
        if (unk.index[d][g.front()] < 0) a = std::min(a, fixed_value[d]), b = std::max(b, fixed_value[d]);
        r = std::max(r, b - a);
      }
    }
    return r;
  };

  SlimFlattenResult out;
  double energy = energy_of(uv);
  out.initial_energy = energy;
  double residual = residual_of(uv);
  std::vector<Vec2> next(uv.size());
  auto face_unknowns = [&](int f, int* ids) {
    for (int j = 0; j < 3; ++j) {
      for (int s = 0; s < 2; ++s) ids[2 * j + s] = var(mesh.faces[f][j], s);
    }
  };
  ProxyPattern pattern =
      proxy_pattern(num_unknowns, nf, face_unknowns, [&](int f) { return ops[f].area == 0.0; });
  SparseMatrix& A = pattern.A;
  SparseSolver solver;
  bool confirm = false;  // the next proxy solve is accurate (see the end of the loop)
  for (int it = 0; it < options.max_iterations && num_unknowns > 0; ++it) {
    // Local step + assembly of the proxy's normal equations (lower triangle).
    std::fill(A.valuePtr(), A.valuePtr() + A.nonZeros(), 0.0);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(num_unknowns);
    for (int f = 0; f < nf; ++f) {
      const FaceOperator& op = ops[f];
      if (op.area == 0.0) continue;
      const auto& t = mesh.faces[f];
      Mat2 J = Mat2::Zero();
      for (int j = 0; j < 3; ++j) J += uv[t[j]] * op.g[j].transpose();
      const Eigen::JacobiSVD<Mat2> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Mat2 U = svd.matrixU();
      const Mat2 R = U * svd.matrixV().transpose();
      Vec2 w;
      for (int i = 0; i < 2; ++i) {
        const double s = svd.singularValues()[i];
        w[i] = std::abs(s - 1.0) < 1e-8 ? 2.0 : std::sqrt((s - std::pow(s, -3.0)) / (s - 1.0));
      }
      const Mat2 W = U * w.asDiagonal() * U.transpose();
      const Mat2 target = W * R;
      // Residual (r, c) = Σ_{j,s} W(r, s) g_j(c) u_j(s) − target(r, c).
      Eigen::Matrix<double, 4, 6> M;
      for (int r = 0; r < 2; ++r) {
        for (int c = 0; c < 2; ++c) {
          for (int j = 0; j < 3; ++j) {
            for (int s = 0; s < 2; ++s) M(2 * r + c, 2 * j + s) = W(r, s) * op.g[j][c];
          }
        }
      }
      Eigen::Vector4d b(target(0, 0), target(0, 1), target(1, 0), target(1, 1));
      const Eigen::Matrix<double, 6, 6> H = op.area / mean_area * (M.transpose() * M);
      const Eigen::Matrix<double, 6, 1> g = op.area / mean_area * (M.transpose() * b);
      int ids[6];
      face_unknowns(f, ids);
      double* values = A.valuePtr();
      const int* slot = &pattern.slot[static_cast<size_t>(f) * 36];
      for (int a = 0; a < 6; ++a) {
        if (ids[a] < 0) continue;
        double r = g[a];
        for (int c = 0; c < 6; ++c) {
          if (ids[c] >= 0) {
            if (const int k = slot[6 * a + c]; k >= 0) values[k] += H(a, c);
          } else {
            r -= H(a, c) * fixed_value[c % 2];
          }
        }
        rhs[ids[a]] += r;
      }
    }
    // The proxy changes little from one iteration to the next: its minimiser
    // is approximated by conjugate gradients preconditioned with the factor
    // of an earlier proxy, from the current map, to a tenth of the starting
    // residual once the constraints hold (before, and to confirm convergence,
    // to 1e-8: the steps must move the constraint groups together); a new
    // factor only when that is not reached within a few steps. The step is cut for injectivity and
    // must lower the energy below either way, so an inexact solve is safe.
    Eigen::VectorXd x(num_unknowns);
    for (int v = 0; v < n; ++v) {
      for (int d = 0; d < 2; ++d) {
        if (const int i = var(v, d); i >= 0) x[i] = uv[v][d];
      }
    }
    const bool feasible = residual <= 1e-9 * size;
    const double forcing = feasible && !confirm ? 0.1 : 0.0;
    const bool solved = solver.factored() && preconditioned_cg(A, rhs, solver, forcing, x);
    if (!solved) {
      solver.refactor(A);  // same pattern every iteration: the ordering is computed once
      x = solver.solve(rhs);
    }

    // Direction towards the proxy minimiser, cut before the first degenerate triangle.
    std::vector<Vec2> dir(uv.size(), Vec2::Zero());
    for (int v = 0; v < n; ++v) {
      if (!used[v]) continue;
      for (int d = 0; d < 2; ++d) {
        const int i = var(v, d);
        dir[v][d] = (i < 0 ? fixed_value[d] : x[i]) - uv[v][d];
      }
    }
    double t_max = kInf;
    for (const auto& t : mesh.faces) {
      t_max = std::min(t_max, first_degenerate_step(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]],
                                                    dir[t[1]] - dir[t[0]], dir[t[2]] - dir[t[0]]));
    }
    double step = std::min(1.0, 0.8 * t_max);
    double e_next = kInf;
    for (int tries = 0; tries < 60; ++tries) {
      for (int v = 0; v < n; ++v) next[v] = used[v] ? Vec2(uv[v] + step * dir[v]) : uv[v];
      e_next = energy_of(next);
      // Before the constraints hold every safe step is taken (it shrinks the
      // residual); after, the energy must not rise.
      if (std::isfinite(e_next) && (!feasible || e_next <= energy)) break;
      step *= 0.5;
    }
    ++out.iterations;
    if (options.on_iteration) options.on_iteration(out.iterations);
    if (!feasible && !(step > 1e-12)) break;  // the constraints cannot be approached without a fold
    if (!std::isfinite(e_next) || (feasible && e_next > energy)) {
      out.converged = true;  // no descent left at this resolution
      break;
    }
    bool flipped = false;
    for (int f = 0; f < nf && !flipped; ++f) flipped = !(signed_uv_area(mesh, next, f) > 0.0);
    if (flipped) break;  // rounding at a nearly degenerate triangle: keep the last injective map
    const double change = std::abs(energy - e_next);
    uv.swap(next);
    energy = e_next;
    residual = residual_of(uv);
    // A small change after an inexact step proves nothing (the step may
    // only have been short): convergence is confirmed by an accurate one.
    if (residual <= 1e-9 * size && feasible && change <= options.tolerance * energy) {
      if (forcing == 0.0) {
        out.converged = true;
        break;
      }
      confirm = true;
    } else {
      confirm = false;
    }
  }
  out.energy = energy;
  out.constraint_residual = residual;
  out.constraints_met = residual <= 1e-9 * std::max(size, 1e-300);
  if (!out.constraints_met) out.converged = false;
  for (int f = 0; f < nf; ++f) {
    if (!(signed_uv_area(mesh, uv, f) > 0.0)) out.flipped_faces.push_back(f);
  }
  out.uv = std::move(uv);
  return out;
}

}  // namespace knitforge
