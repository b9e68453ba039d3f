#include "knitforge/sim/predict_shape.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

namespace {

Vec3 at(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

int dominant_axis(const Vec3& d) {
  int a = 0;
  d.cwiseAbs().maxCoeff(&a);
  return a;
}

// Signed clearance of p from the body: the distance, negative on the inner
// side of the closest face (or when touching).
double clearance(const KinematicBody& body, const Vec3& p) {
  const auto q = body.closest_point_within(p, INFINITY);
  if (!q) return INFINITY;
  const double d = std::sqrt(q->distance2);
  const double side = (p - q->where.point).dot(body.face_normal(q->face));
  return side > 0 ? d : -d;
}

}  // namespace

void set_predict_iterations(PredictOptions& options, int newton_iterations) {
  options.equilibrium.newton.max_iterations = newton_iterations;
  options.equilibrium.quasi_newton.max_iterations = kQuasiNewtonPerNewton * newton_iterations;
}

std::vector<char> free_body_constraints(const Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size() / 3);
  std::vector<char> held(x.size(), 0);
  if (n == 0) return held;
  const int a = 0;
  int b = a;
  for (int v = 0; v < n; ++v)
    if ((at(x, v) - at(x, a)).squaredNorm() > (at(x, b) - at(x, a)).squaredNorm()) b = v;
  for (int k = 0; k < 3; ++k) held[3 * a + k] = 1;
  if (b == a) return held;
  const Vec3 d = at(x, b) - at(x, a);
  const int along = dominant_axis(d);
  for (int k = 0; k < 3; ++k)
    if (k != along) held[3 * b + k] = 1;
  // The vertex farthest from the line ab holds the rotation about it.
  int c = a;
  double best = 0;
  for (int v = 0; v < n; ++v) {
    const double r = d.cross(at(x, v) - at(x, a)).squaredNorm();
    if (r > best) best = r, c = v;
  }
  if (c == a) return held;
  const Vec3 normal = d.cross(at(x, c) - at(x, a));
  held[3 * c + dominant_axis(normal)] = 1;
  return held;
}

double lift_clear_of_body(const KinematicBody& body, const Eigen::VectorXd& x, double gap_mm, double max_lift_mm) {
  const int n = static_cast<int>(x.size() / 3);
  auto clear_at = [&](double lift) {
    for (int v = 0; v < n; ++v) {
      if (clearance(body, at(x, v) + Vec3(0, 0, lift)) < gap_mm) return false;
    }
    return true;
  };
  if (clear_at(0.0)) return 0.0;
  // Doubling to a clear lift, then bisection to within 1 % of the gap.
  double lo = 0.0, hi = std::max(gap_mm, 1e-3);
  while (!clear_at(hi)) {
    lo = hi;
    hi *= 2;
    if (hi > max_lift_mm) {
      throw InvalidInput(fmt::format(
          "predict: the piece cannot be lifted clear of the support (not clear even {:.1f} mm above its start); "
          "place it above the support, outside it",
          max_lift_mm));
    }
  }
  while (hi - lo > 0.01 * gap_mm) {
    const double mid = 0.5 * (lo + hi);
    (clear_at(mid) ? hi : lo) = mid;
  }
  return hi;
}

PredictResult predict_shape(const StitchMesh& designed, const KnitParams& params, const KinematicBody* support,
                            const PredictOptions& options) {
  const bool on_support = support && !support->empty();
  if (options.gravity && !on_support) {
    throw InvalidInput("predict: gravity needs a support to rest on (give --on SUPPORT), or switch gravity off");
  }
  if (!(options.start_gap_mm > 0 && options.start_gap_mm < options.equilibrium.contact.distance_mm)) {
    throw InvalidInput(fmt::format("predict: the start gap {} mm must be positive and below the contact distance {} mm",
                                   options.start_gap_mm, options.equilibrium.contact.distance_mm));
  }
  const SimModel model = build_sim_model(designed, params, options.model);
  SimWorkspace ws(model);
  PredictResult out;
  out.num_elements = model.num_elements();
  Eigen::VectorXd x0(3 * model.num_vertices());
  for (int v = 0; v < model.num_vertices(); ++v) x0.segment<3>(3 * v) = model.rest_positions[v];
  EquilibriumOptions eo = options.equilibrium;
  if (on_support) {
    const BoundingBox box = [&] {
      TriMesh t;
      t.vertices = model.rest_positions;
      return bounding_box(t);
    }();
    if (options.centre_on_support) {
      const Vec3 shift = bounding_box(support->mesh()).center() - box.center();
      for (int v = 0; v < model.num_vertices(); ++v) x0.segment<2>(3 * v) += shift.head<2>();
    }
    out.lift_mm = lift_clear_of_body(*support, x0, options.start_gap_mm, 10.0 * std::max(box.diagonal(), 1.0));
    for (int v = 0; v < model.num_vertices(); ++v) x0[3 * v + 2] += out.lift_mm;
    if (options.gravity) {
      eo.gravity_mm_s2 = Vec3(0, 0, -9810.0);
      const Timer t;
      StepOptions so = options.settle;
      so.gravity_mm_s2 = eo.gravity_mm_s2;
      so.contact = eo.contact;
      SimState s{x0, Eigen::VectorXd::Zero(x0.size()), 0.0};
      double last_kinetic = 0.0;
      out.settled = false;
      for (int k = 0; k < options.max_settle_steps; ++k) {
        s = step_simulation(ws, s, *support, {}, {}, so).state;
        ++out.settle_steps;
        double kinetic = 0.0, speed = 0.0;
        for (int v = 0; v < model.num_vertices(); ++v) {
          const double v2 = s.velocities_mm_s.segment<3>(3 * v).squaredNorm();
          kinetic += 0.5 * model.vertex_mass_kg[v] * v2;
          speed = std::max(speed, std::sqrt(v2));
        }
        if (k >= 2 && speed < options.settle_speed_mm_s) {
          out.settled = true;
          break;
        }
        // Kinetic damping: past a peak of the kinetic energy, start again at rest.
        if (kinetic < last_kinetic) {
          s.velocities_mm_s.setZero();
          kinetic = 0.0;
        }
        last_kinetic = kinetic;
      }
      x0 = s.positions_mm;
      out.settle_seconds = t.seconds();
    }
  } else {
    eo.held_coordinates = free_body_constraints(x0);
    eo.gravity_mm_s2 = Vec3::Zero();
  }
  out.solve = solve_equilibrium(ws, x0, on_support ? support : nullptr, eo);
  out.predicted = designed;
  const Eigen::VectorXd& x = out.solve.positions_mm;
  for (int v = 0; v < model.num_vertices(); ++v) out.predicted.vertices[v] = x.segment<3>(3 * v);
  const int ns = designed.num_stitches();
  out.stitch_stress_kpa.assign(ns, 0.0);
  out.stitch_course_strain.assign(ns, -INFINITY);
  out.stitch_wale_strain.assign(ns, -INFINITY);
  for (const MembraneElement& e : model.elements) {
    const MembraneStress s =
        membrane_stress(at(x, e.v[0]), at(x, e.v[1]), at(x, e.v[2]), e, model.materials[e.material]);
    out.stitch_stress_kpa[e.stitch] = std::max(out.stitch_stress_kpa[e.stitch], s.principal_max_kpa);
    out.stitch_course_strain[e.stitch] = std::max(out.stitch_course_strain[e.stitch], s.course_strain);
    out.stitch_wale_strain[e.stitch] = std::max(out.stitch_wale_strain[e.stitch], s.wale_strain);
  }
  return out;
}

}  // namespace knitforge
