#include "knitforge/geometry/arap_flatten.h"

#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "knitforge/geometry/sparse_solver.h"
#include "knitforge/geometry/tutte_embedding.h"
#include "knitforge/util/errors.h"

namespace knitforge {

std::array<Vec2, 3> isometric_triangle(const TriMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  const Vec3 e1 = mesh.vertices[t[1]] - mesh.vertices[t[0]];
  const Vec3 e2 = mesh.vertices[t[2]] - mesh.vertices[t[0]];
  const double l1 = e1.norm();
  std::array<Vec2, 3> x{Vec2::Zero(), Vec2(l1, 0.0), Vec2::Zero()};
  if (l1 > 0.0) {
    const double along = e2.dot(e1) / l1;
    const double up = e1.cross(e2).norm() / l1;
    x[2] = Vec2(along, up);
  } else {
    x[2] = Vec2(0.0, e2.norm());
  }
  return x;
}

double signed_uv_area(const TriMesh& mesh, const std::vector<Vec2>& uv, int f) {
  const auto& t = mesh.faces[f];
  const Vec2 a = uv[t[1]] - uv[t[0]];
  const Vec2 b = uv[t[2]] - uv[t[0]];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

bool has_flipped_face(const TriMesh& mesh, const std::vector<Vec2>& uv) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    if (!(signed_uv_area(mesh, uv, f) > 0.0)) return true;
  }
  return false;
}

namespace {

// Union-find over vertices for the equal-coordinate groups.
int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

// One coordinate's reduced system: vertex -> unknown (or fixed).
struct CoordinateSystem {
  std::vector<int> unknown;  // per vertex, -1 when fixed (pinned group)
  int num_unknowns = 0;
  double fixed_value = 0.0;
  SparseSolver solver;
};

void check_pairs(const std::vector<std::pair<int, int>>& pairs, int n, const char* name) {
  for (size_t i = 0; i < pairs.size(); ++i) {
    const auto [a, b] = pairs[i];
    if (a < 0 || a >= n || b < 0 || b >= n) {
      throw InvalidInput(std::string("arap_flatten: ") + name + " constraint " + std::to_string(i) +
                         " names vertex " + std::to_string(a < 0 || a >= n ? a : b) + ", outside [0, " +
                         std::to_string(n) + ")");
    }
  }
}

CoordinateSystem build_system(const TriMesh& mesh, const std::vector<double>& weight,
                              const std::vector<std::pair<int, int>>& pairs, int pinned, double pinned_value,
                              const std::vector<char>& used) {
  const int n = mesh.num_vertices();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : pairs) {
    const int ra = find_root(parent, a);
    const int rb = find_root(parent, b);
    if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  CoordinateSystem sys;
  sys.fixed_value = pinned_value;
  sys.unknown.assign(n, -1);
  const int pinned_root = find_root(parent, pinned);
  std::vector<int> root_unknown(n, -1);
  for (int v = 0; v < n; ++v) {
    if (!used[v]) continue;
    const int r = find_root(parent, v);
    if (r == pinned_root) continue;
    if (root_unknown[r] < 0) root_unknown[r] = sys.num_unknowns++;
    sys.unknown[v] = root_unknown[r];
  }
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(mesh.num_faces()) * 9);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    for (int j = 0; j < 3; ++j) {
      const int uj = sys.unknown[t[j]];
      if (uj < 0) continue;
      for (int k = 0; k < 3; ++k) {
        const int uk = sys.unknown[t[k]];
        if (uk < 0) continue;
        trip.emplace_back(uj, uk, weight[f] * ((j == k ? 1.0 : 0.0) - 1.0 / 3.0));
      }
    }
  }
  if (sys.num_unknowns > 0) {
    SparseMatrix A(sys.num_unknowns, sys.num_unknowns);
    A.setFromTriplets(trip.begin(), trip.end());
    sys.solver.factor(A);
  }
  return sys;
}

}  // namespace

ArapFlattenResult arap_flatten(const TriMesh& mesh, const ArapFlattenOptions& options) {
  const int n = mesh.num_vertices();
  const int nf = mesh.num_faces();
  if (nf == 0) throw InvalidInput("arap_flatten: the mesh has no faces");
  if (options.max_iterations < 0) throw InvalidInput("arap_flatten: max_iterations must be >= 0");
  if (!(options.tolerance >= 0.0)) throw InvalidInput("arap_flatten: tolerance must be >= 0");
  for (const auto& t : mesh.faces) {
    for (int v : t) {
      if (v < 0 || v >= n) throw InvalidInput("arap_flatten: a face uses a vertex index out of range");
    }
  }
  check_pairs(options.equal_x, n, "equal_x");
  check_pairs(options.equal_y, n, "equal_y");

  std::vector<Vec2> uv;
  if (options.initial.empty()) {
    uv = tutte_embedding(mesh).uv;
  } else {
    if (static_cast<int>(options.initial.size()) != n) {
      throw InvalidInput("arap_flatten: " + std::to_string(options.initial.size()) +
                         " initial positions for " + std::to_string(n) + " vertices");
    }
    uv = options.initial;
    for (int v = 0; v < n; ++v) {
      if (!uv[v].allFinite()) {
        throw InvalidInput("arap_flatten: initial position of vertex " + std::to_string(v) +
                           " is not finite");
      }
    }
  }

  // Frames, centred, and weights (3D areas, normalised by their mean for
  // conditioning; the reported energies use the true areas).
  std::vector<std::array<Vec2, 3>> frame(nf);
  std::vector<double> area(nf);
  double total = 0.0;
  for (int f = 0; f < nf; ++f) {
    auto x = isometric_triangle(mesh, f);
    const Vec2 c = (x[0] + x[1] + x[2]) / 3.0;
    for (auto& p : x) p -= c;
    frame[f] = x;
    area[f] = 0.5 * std::abs(x[1].x() * x[2].y() - x[1].y() * x[2].x());
    total += area[f];
  }
  if (!(total > 0.0)) throw InvalidInput("arap_flatten: the mesh has zero area");
  const double mean_area = total / nf;
  std::vector<double> weight(nf);
  double area_sq = 0.0;
  for (int f = 0; f < nf; ++f) {
    weight[f] = area[f] / mean_area;
    area_sq += area[f] * area[f];
  }

  std::vector<char> used(n, 0);
  for (const auto& t : mesh.faces) {
    for (int v : t) used[v] = 1;
  }
  int pinned = options.pinned_vertex;
  if (pinned >= n) {
    throw InvalidInput("arap_flatten: pinned_vertex " + std::to_string(pinned) + " is out of range");
  }
  if (pinned < 0 || !used[pinned]) {
    Vec2 centroid = Vec2::Zero();
    int count = 0;
    for (int v = 0; v < n; ++v) {
      if (used[v]) {
        centroid += uv[v];
        ++count;
      }
    }
    centroid /= std::max(count, 1);
    double best = std::numeric_limits<double>::infinity();
    for (int v = 0; v < n; ++v) {
      if (used[v] && (uv[v] - centroid).squaredNorm() < best) {
        best = (uv[v] - centroid).squaredNorm();
        pinned = v;
      }
    }
  }
  // The pinned vertex's group keeps the pinned vertex's coordinate; the rest
  // of the group is moved onto it now so the constraints hold from the start.
  const bool no_constraints = options.equal_x.empty() && options.equal_y.empty();
  CoordinateSystem sys[2];
  sys[0] = build_system(mesh, weight, options.equal_x, pinned, uv[pinned].x(), used);
  if (no_constraints) {
    sys[1].unknown = sys[0].unknown;
    sys[1].num_unknowns = sys[0].num_unknowns;
    sys[1].fixed_value = uv[pinned].y();
  } else {
    sys[1] = build_system(mesh, weight, options.equal_y, pinned, uv[pinned].y(), used);
  }

  std::vector<Mat2> rot(nf, Mat2::Identity());
  auto local_step = [&]() {
    double energy = 0.0;
    for (int f = 0; f < nf; ++f) {
      const auto& t = mesh.faces[f];
      const Vec2 c = (uv[t[0]] + uv[t[1]] + uv[t[2]]) / 3.0;
      Mat2 S = Mat2::Zero();  // Σ (u - ū)(x - x̄)^T
      for (int j = 0; j < 3; ++j) S += (uv[t[j]] - c) * frame[f][j].transpose();
      // Rotation maximising tr(R^T S): angle atan2(S10 - S01, S00 + S11),
      // i.e. (cos, sin) = (S00 + S11, S10 - S01) normalised.
      const double a = S(0, 0) + S(1, 1);
      const double b = S(1, 0) - S(0, 1);
      const double len = std::hypot(a, b);
      const double cs = len > 0.0 ? a / len : 1.0;
      const double sn = len > 0.0 ? b / len : 0.0;
      rot[f] << cs, -sn, sn, cs;
      for (int j = 0; j < 3; ++j) energy += area[f] * ((uv[t[j]] - c) - rot[f] * frame[f][j]).squaredNorm();
    }
    return energy;
  };
  const bool shared = no_constraints;
  auto global_step = [&]() {
    if (shared && sys[0].num_unknowns > 0) {
      // Same matrix and unknowns for x and y: one solve with two columns.
      const CoordinateSystem& s = sys[0];
      Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(s.num_unknowns, 2);
      for (int f = 0; f < nf; ++f) {
        const auto& t = mesh.faces[f];
        bool any_fixed = false;
        for (int j = 0; j < 3; ++j) any_fixed = any_fixed || s.unknown[t[j]] < 0;
        for (int j = 0; j < 3; ++j) {
          const int uj = s.unknown[t[j]];
          if (uj < 0) continue;
          Vec2 r = weight[f] * (rot[f] * frame[f][j]);
          if (any_fixed) {
            for (int k = 0; k < 3; ++k) {
              if (s.unknown[t[k]] < 0) {
                r -= weight[f] * ((j == k ? 1.0 : 0.0) - 1.0 / 3.0) *
                     Vec2(sys[0].fixed_value, sys[1].fixed_value);
              }
            }
          }
          rhs(uj, 0) += r.x();
          rhs(uj, 1) += r.y();
        }
      }
      const Eigen::MatrixXd x = s.solver.solve_columns(rhs);
      for (int v = 0; v < n; ++v) {
        if (!used[v]) continue;
        uv[v] = s.unknown[v] < 0 ? Vec2(sys[0].fixed_value, sys[1].fixed_value)
                                 : Vec2(x(s.unknown[v], 0), x(s.unknown[v], 1));
      }
      return;
    }
    for (int d = 0; d < 2; ++d) {
      const CoordinateSystem& s = sys[d];
      if (s.num_unknowns == 0) continue;
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(s.num_unknowns);
      for (int f = 0; f < nf; ++f) {
        const auto& t = mesh.faces[f];
        for (int j = 0; j < 3; ++j) {
          const int uj = s.unknown[t[j]];
          if (uj < 0) continue;
          rhs[uj] += weight[f] * (rot[f] * frame[f][j])[d];
          // Fixed (pinned-group) neighbours move to the right-hand side.
          for (int k = 0; k < 3; ++k) {
            if (s.unknown[t[k]] < 0) {
              rhs[uj] -= weight[f] * ((j == k ? 1.0 : 0.0) - 1.0 / 3.0) * s.fixed_value;
            }
          }
        }
      }
      const Eigen::VectorXd x = s.solver.solve(rhs);
      for (int v = 0; v < n; ++v) {
        if (!used[v]) continue;
        uv[v][d] = s.unknown[v] < 0 ? s.fixed_value : x[s.unknown[v]];
      }
    }
  };

  ArapFlattenResult out;
  double energy = local_step();
  out.initial_energy = energy;
  const double floor = 1e-14 * area_sq;
  bool has_constraints = !options.equal_x.empty() || !options.equal_y.empty();
  int folded_in_a_row = 0;
  for (int it = 0; it < options.max_iterations; ++it) {
    global_step();
    const double next = local_step();
    ++out.iterations;
    if (options.on_iteration) options.on_iteration(out.iterations);
    if (options.stop_after_folded_iterations > 0) {
      folded_in_a_row = has_flipped_face(mesh, uv) ? folded_in_a_row + 1 : 0;
      if (folded_in_a_row >= options.stop_after_folded_iterations) {
        energy = next;
        out.stopped_folded = true;
        break;
      }
    }
    const double change = std::abs(energy - next);
    energy = next;
    // With constraints the first step may raise the energy (it enforces them).
    if ((change <= options.tolerance * std::max(energy, floor) || energy <= floor) &&
        !(has_constraints && it == 0)) {
      out.converged = true;
      break;
    }
  }
  if (options.max_iterations == 0) out.converged = energy <= floor;
  out.energy = energy;
  out.relative_energy = area_sq > 0.0 ? energy / area_sq : 0.0;
  for (int f = 0; f < nf; ++f) {
    if (!(signed_uv_area(mesh, uv, f) > 0.0)) out.flipped_faces.push_back(f);
  }
  out.uv = std::move(uv);
  return out;
}

}  // namespace knitforge
