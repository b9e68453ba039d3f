#include "knitforge/design/shortcolumn/optimise_boundary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/design/shortcolumn/divergence_metric.h"
#include "knitforge/design/shortcolumn/feasible_set.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/isotropic_remesh.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

namespace {

double mirror_error(const TriMesh& m, const BoundaryParameterisation& bp, const MirrorPlane& pl) {
  const Vec3 n = pl.normal.normalized();
  const double off = pl.offset / pl.normal.norm();
  double sum = 0.0;
  for (int k = 0; k < bp.size(); ++k) {
    const Vec3& x = m.vertices[bp.loop[k]];
    const Vec3 y = x - 2.0 * (n.dot(x) - off) * n;
    double best = std::numeric_limits<double>::infinity();
    for (int j = 0; j < bp.size(); ++j) {
      const Vec3& a = m.vertices[bp.loop[j]];
      const Vec3& b = m.vertices[bp.loop[(j + 1) % bp.size()]];
      best = std::min(best, (closest_point_on_segment(y, a, b) - y).norm());
    }
    sum += best;
  }
  return sum / bp.size();
}

}  // namespace

MirrorPlane mirror_plane(const TriMesh& surface, double& mean_error, const std::optional<MirrorPlane>& given) {
  const BoundaryParameterisation bp = parameterise_boundary(surface);
  if (given) {
    if (!(given->normal.norm() > 0.0) || !given->normal.allFinite() || !std::isfinite(given->offset))
      throw InvalidInput("mirror plane: the normal must be non-zero and finite");
    mean_error = mirror_error(surface, bp, *given);
    return *given;
  }
  const BoundingBox box = bounding_box(surface);
  const MirrorPlane px{Vec3::UnitX(), box.center().x()}, py{Vec3::UnitY(), box.center().y()};
  const double ex = mirror_error(surface, bp, px), ey = mirror_error(surface, bp, py);
  mean_error = std::min(ex, ey);
  return ex <= ey ? px : py;
}

TriMesh optimisation_proxy(const TriMesh& surface, int faces, double* edge_length) {
  if (edge_length) *edge_length = 0.0;
  if (faces <= 0 || faces >= surface.num_faces()) return surface;
  RemeshOptions ro;
  ro.target_edge_length = std::sqrt(4.0 * total_area(surface) / (std::sqrt(3.0) * faces));
  ro.iterations = 5;
  if (edge_length) *edge_length = ro.target_edge_length;
  return isotropic_remesh(surface, ro);
}

std::vector<int> distinct_alternatives(const std::vector<BoundaryEvaluation>& history, int k, double distance) {
  std::vector<int> order(history.size());
  for (size_t i = 0; i < history.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return history[a].value < history[b].value; });
  std::vector<int> picked;
  for (int i : order) {
    if (static_cast<int>(picked.size()) >= k) break;
    bool far = true;
    for (int j : picked) far = far && boundary_distance(history[i].evaluated, history[j].evaluated) >= distance;
    if (far) picked.push_back(i);
  }
  return picked;
}

BoundaryOptimisation optimise_boundary(const TriMesh& surface, const BoundaryOptimisationOptions& o) {
  const Timer total;
  if (!(o.stitch_width > 0.0) || !std::isfinite(o.stitch_width))
    throw InvalidInput("boundary optimisation: the stitch width must be positive");
  if (o.alternatives < 1) throw InvalidInput("boundary optimisation: keep at least one alternative (--alternatives >= 1)");
  if (!(o.distinct_distance >= 0.0)) throw InvalidInput("boundary optimisation: distinct_distance must be >= 0");
  require_disk(surface, "boundary optimisation");
  BoundaryOptimisation r;
  Timer t;
  const TriMesh proxy = optimisation_proxy(surface, o.proxy_faces, &r.proxy_edge_length);
  r.proxy_faces = proxy.num_faces();
  r.proxy_vertices = proxy.num_vertices();
  HarmonicFieldSolver solver(proxy);
  const DivergenceOperator div(proxy);
  r.seconds_proxy = t.seconds();
  const double scale = 1.5 / o.stitch_width;

  TurboProblem pr;
  std::function<BoundaryVector(const Eigen::VectorXd&)> to_b, to_feasible_b;  // any x; a feasible x
  if (o.symmetric) {
    r.symmetric = true;
    r.mirror = mirror_plane(surface, r.mirror_error, o.mirror);
    const double diag = bounding_box(surface).diagonal();
    if (r.mirror_error > 0.02 * diag)
      throw InvalidInput(fmt::format(
          "symmetric optimisation: the boundary is not mirror-symmetric about the plane ({:.3g}, {:.3g}, {:.3g}) . x = "
          "{:.4g} mm: the mirrored boundary lies {:.3g} mm from it on average (more than 2 % of the {:.4g} mm "
          "diagonal); give the symmetry plane or drop --symmetric",
          r.mirror.normal.x(), r.mirror.normal.y(), r.mirror.normal.z(), r.mirror.offset, r.mirror_error, diag));
    // Where the plane crosses the boundary loop (parameters).
    const BoundaryParameterisation& bp = solver.boundary();
    const Vec3 n = r.mirror.normal.normalized();
    const double off = r.mirror.offset / r.mirror.normal.norm();
    std::vector<double> cross;
    const int nb = bp.size();
    for (int k = 0; k < nb; ++k) {
      const double s0 = n.dot(proxy.vertices[bp.loop[k]]) - off;
      const double s1 = n.dot(proxy.vertices[bp.loop[(k + 1) % nb]]) - off;
      const double t0 = bp.t[k], t1 = k + 1 < nb ? bp.t[k + 1] : 1.0;
      if (s0 == 0.0) {
        cross.push_back(t0);
      } else if ((s0 < 0.0) != (s1 < 0.0) && s1 != 0.0) {
        cross.push_back(t0 + (t1 - t0) * s0 / (s0 - s1));
      }
    }
    if (cross.size() != 2)
      throw InvalidInput(fmt::format("symmetric optimisation: the mirror plane crosses the boundary {} times; it must "
                                     "cross it exactly twice",
                                     cross.size()));
    r.mirror_p = cross[0];
    r.mirror_gap = cross[1] - cross[0];
    const LinearConstraints k = symmetric_constraints(r.mirror_gap);
    const double w = std::min(r.mirror_gap, 1.0 - r.mirror_gap) - kFeasibleMargin;
    pr.lower = Eigen::Vector2d(0.0, 0.0);
    pr.upper = Eigen::Vector2d(w, w);
    pr.project = [k](const Eigen::VectorXd& x) { return project_onto_constraints(k, x); };
    pr.sample_feasible = [w](const Eigen::VectorXd& u) {
      const double s0 = std::min(u[0], u[1]), s1 = std::max(u[0], u[1]);
      return Eigen::VectorXd(Eigen::Vector2d(w * s0, w * (s1 - s0)));
    };
    const double p = r.mirror_p, g = r.mirror_gap;
    // Half-widths a hair below 0 (the projection's rounding) would swap b0, b1.
    to_b = [p, g](const Eigen::VectorXd& x) {
      return symmetric_boundary(p, g, std::max(x[0], 0.0), std::max(x[1], 0.0));
    };
  } else {
    const LinearConstraints k = boundary_constraints();
    pr.lower = Eigen::Vector4d(0.0, 0.0, 0.0, 0.0);
    pr.upper = Eigen::Vector4d(1.0, 2.0, 2.0, 2.0);
    pr.project = [k](const Eigen::VectorXd& x) { return project_onto_constraints(k, x); };
    pr.sample_feasible = [](const Eigen::VectorXd& u) {
      const BoundaryVector b = boundary_from_unit(Eigen::Vector4d(u[0], u[1], u[2], u[3]));
      return Eigen::VectorXd(Eigen::Vector4d(b[0], b[1], b[2], b[3]));
    };
    to_b = [](const Eigen::VectorXd& x) { return BoundaryVector{x[0], x[1], x[2], x[3]}; };
    // The projection's rounding can leave b3 a hair below b2; snap it.
    to_feasible_b = [](const Eigen::VectorXd& x) { return snap_feasible(BoundaryVector{x[0], x[1], x[2], x[3]}); };
  }
  if (!to_feasible_b) to_feasible_b = to_b;
  std::vector<double> metric_of;  // per evaluation, in order
  pr.objective = [&](const Eigen::VectorXd& x) {
    // A b the proxy's boundary cannot place (R_e squeezed next to R_s
    // between two boundary vertices) scores as the worst b so far: it is
    // feasible in eq. 3.8 but has no field on this mesh.
    double m = 0.0;
    bool placed = true;
    try {
      m = div.total(solver.solve(to_feasible_b(x)).value);
    } catch (const TopologyError&) {
      placed = false;
    }
    if (!placed) {
      ++r.unplaceable;
      m = 0.0;
      for (double v : metric_of) m = std::max(m, v);
      if (metric_of.empty()) m = 1e3 * o.stitch_width;  // no evaluation yet: 1500 estimated transfers
    }
    metric_of.push_back(m);
    return scale * m;
  };
  TurboOptions to = o.turbo;
  to.on_evaluation = [&](const TurboEvaluation& e) {
    BoundaryEvaluation be;
    be.suggested = to_b(e.suggested);
    be.evaluated = canonical_boundary(to_feasible_b(e.evaluated));
    be.projected = e.projected;
    be.initial = e.initial;
    be.region = e.region;
    be.metric = metric_of[static_cast<size_t>(e.index)];
    be.value = e.value;
    be.penalised = e.penalised;
    be.best = e.best;
    be.trust_length = e.trust_length;
    r.history.push_back(be);
    if (o.progress) o.progress(r.history.back(), static_cast<int>(r.history.size()) - 1);
  };
  t.reset();
  const TurboResult tr = turbo_optimize(pr, to);
  r.seconds_evaluations = t.seconds();
  r.regions = tr.regions;
  r.best = canonical_boundary(to_feasible_b(tr.best_x));
  r.best_value = tr.best_value;
  r.alternatives = distinct_alternatives(r.history, o.alternatives, o.distinct_distance);
  r.seconds = total.seconds();
  return r;
}

}  // namespace knitforge
