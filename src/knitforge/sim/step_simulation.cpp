#include "knitforge/sim/step_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "knitforge/sim/bending_energy.h"
#include "knitforge/sim/collision_free_step.h"
#include "knitforge/sim/contact_candidates.h"
#include "knitforge/sim/friction_energy.h"
#include "knitforge/sim/inertia_energy.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

SimWorkspace::SimWorkspace(const SimModel& model) : model_(&model), pattern_(build_hessian_pattern(model)) {
  // One symbolic analysis for every Hessian of the model: a failed
  // (indefinite) factorisation no longer makes the next one analyse again.
  if (pattern_->nonzeros() > 0) solver_.analyze(pattern_->matrix(std::vector<double>(pattern_->nonzeros(), 0.0)));
  const int n = model.num_vertices();
  fixed_.assign(3 * static_cast<size_t>(n), 0);
  pinned_.assign(n, 0);
  for (int v : model.pinned) {
    if (v < 0 || v >= n) throw InvalidInput(fmt::format("simulation: pinned vertex {} out of range (0..{})", v, n - 1));
    pinned_[v] = 1;
    for (int k = 0; k < 3; ++k) fixed_[3 * v + k] = 1;
  }
}

double elastic_energy(const SimModel& model, const Eigen::VectorXd& x) {
  EnergyEval ev(model.num_vertices(), Derivatives::Value);
  add_membrane_energy(model, x, PsdProjection::None, ev);
  add_bending_energy(model, x, ev);
  return ev.value;
}

namespace {

void check_contact(const ContactParams& c) {
  if (!(c.distance_mm > 0 && std::isfinite(c.distance_mm) && c.barrier_pressure_kpa > 0 &&
        std::isfinite(c.barrier_pressure_kpa) && c.friction >= 0 && std::isfinite(c.friction) &&
        c.friction_velocity_mm_s > 0 && std::isfinite(c.friction_velocity_mm_s))) {
    throw InvalidInput(fmt::format(
        "simulation: contact distance {} mm, barrier pressure {} kPa and friction velocity {} mm/s must be positive, "
        "friction {} >= 0",
        c.distance_mm, c.barrier_pressure_kpa, c.friction_velocity_mm_s, c.friction));
  }
}

void accumulate(NewtonTimings& a, const NewtonTimings& b) {
  a.evaluate += b.evaluate;
  a.factor += b.factor;
  a.max_step += b.max_step;
  a.line_search += b.line_search;
}

// One step of length h without splitting; returns false when the body's
// motion would pass through a vertex of the carried start.
bool try_step(SimWorkspace& ws, const SimState& state, const KinematicBody& body, const std::vector<Vec3>& body_end,
              const std::vector<Vec3>& pin_targets, const StepOptions& o, double h, StepResult& out) {
  const SimModel& model = ws.model();
  const Eigen::VectorXd& xn = state.positions_mm;
  const double dhat = o.contact.distance_mm;
  const bool has_body = !body.empty();
  const bool moves = has_body && !body_end.empty();
  // The start of the Newton solve: carried by the body near it, pins at their targets.
  Eigen::VectorXd x0 = xn;
  double body_speed = 0.0;
  if (moves) {
    for (size_t k = 0; k < body_end.size(); ++k) body_speed = std::max(body_speed, (body_end[k] - body.mesh().vertices[k]).norm());
  }
  KinematicBody end_body = body;
  if (moves) end_body.move_to(body_end);
  if (moves && body_speed > 0) {
    for (int v = 0; v < model.num_vertices(); ++v) {
      if (ws.pinned_vertices()[v]) continue;
      const auto q = body.closest_point_within(xn.segment<3>(3 * v), dhat + 2 * body_speed);
      if (q) x0.segment<3>(3 * v) += end_body.point(q->face, q->where.bary) - q->where.point;
    }
    // Carrying a vertex with its closest face can drive it into another part
    // of the body (a vertex in the crease of an elbow, carried by the forearm
    // into the upper arm): such a vertex starts where it is instead, and the
    // check below decides whether the body's motion lets it.
    std::vector<double> free_fraction;
    collision_free_step(body, body_end, xn, x0, ws.pinned_vertices(), &free_fraction);
    for (int v = 0; v < model.num_vertices(); ++v) {
      if (free_fraction[v] < 1.0) x0.segment<3>(3 * v) = xn.segment<3>(3 * v);
    }
  }
  for (size_t k = 0; k < model.pinned.size() && k < pin_targets.size(); ++k) {
    x0.segment<3>(3 * model.pinned[k]) = pin_targets[k];
  }
  if (has_body) {
    const double t = moves ? collision_free_step(body, body_end, xn, x0, ws.pinned_vertices())
                           : collision_free_step(body, xn, x0, ws.pinned_vertices());
    if (t < 1.0) return false;
  }
  const Eigen::VectorXd xt = predict_positions(xn, state.velocities_mm_s, h, o.gravity_mm_s2);
  Eigen::VectorXd x = x0;
  out.converged = true;
  for (int fi = 0; fi < std::max(1, o.friction_iterations); ++fi) {
    std::vector<FrictionPair> friction;
    if (has_body && o.contact.friction > 0) {
      const Eigen::VectorXd& lag = fi == 0 ? xn : x;
      const std::vector<ContactPair> c =
          find_contact_candidates(fi == 0 ? body : end_body, lag, dhat, ws.pinned_vertices());
      friction = build_friction_pairs(model, c, fi == 0 ? body : end_body, end_body, lag, o.contact);
      if (fi > 0) {
        for (FrictionPair& f : friction) f.body_motion = Vec3::Zero();
        // Lagged at the end pose: the body's motion over the step is that of
        // the point of the pair's own part closest to the vertex at the start.
        for (FrictionPair& f : friction) {
          const auto q = body.closest_point_of_part_within(xn.segment<3>(3 * f.vertex), f.part, dhat + 2 * body_speed);
          if (q) f.body_motion = end_body.point(q->face, q->where.bary) - q->where.point;
        }
      }
    }
    // The incremental potential with the element Hessians projected by `projection`.
    auto potential = [&](PsdProjection projection) {
      return [&, projection](const Eigen::VectorXd& y, Derivatives what) {
        EnergyEval ev(model.num_vertices(), what, what == Derivatives::Hessian ? ws.pattern() : nullptr);
        add_inertia_energy(model, y, xt, xn, h, ev);
        add_membrane_energy(model, y, projection, ev);
        add_bending_energy(model, y, ev, projection);
        if (has_body) {
          const std::vector<ContactPair> pairs = find_contact_candidates(end_body, y, dhat, ws.pinned_vertices());
          add_contact_energy(model, pairs, end_body, y, o.contact, ev);
          if (std::isfinite(ev.value)) add_friction_energy(friction, y, xn, h, o.contact, ev);
        }
        return ev;
      };
    };
    const EvaluateEnergy evaluate = potential(o.projection);
    const MaxStep max_step = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return has_body ? collision_free_step(end_body, a, b, ws.pinned_vertices()) : 1.0;
    };
    if (o.quasi_newton.max_iterations > 0) {
      QuasiNewtonOptions qo = o.quasi_newton;
      qo.force_tolerance_mn = o.newton.force_tolerance_mn;
      const QuasiNewtonResult q =
          quasi_newton_solve(x, ws.fixed_dofs(), evaluate, potential(PsdProjection::Clamp), max_step, qo, ws.solver());
      x = q.x;
      out.quasi_newton_iterations += q.iterations;
      out.factorizations += q.factorizations;
      accumulate(out.seconds, q.seconds);
    }
    const NewtonResult r = newton_solve(x, ws.fixed_dofs(), evaluate, max_step, o.newton, ws.solver());
    x = r.x;
    out.converged = out.converged && r.converged;
    out.newton_iterations += r.iterations;
    out.factorizations += r.factorizations;
    out.solves_at_iteration_limit += r.stop_reason == "iteration limit" ? 1 : 0;
    out.max_force_mn = r.max_force_mn;
    accumulate(out.seconds, r.seconds);
  }
  out.state.positions_mm = x;
  out.state.velocities_mm_s = (x - xn) / h;
  out.state.time_s = state.time_s + h;
  if (has_body) {
    out.contacts = static_cast<int>(find_contact_candidates(end_body, x, dhat, ws.pinned_vertices()).size());
    out.min_distance_mm = min_distance_to_body(end_body, x, dhat, ws.pinned_vertices());
  } else {
    out.min_distance_mm = std::numeric_limits<double>::infinity();
  }
  return true;
}

StepResult step_recursive(SimWorkspace& ws, const SimState& state, const KinematicBody& body,
                          const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets,
                          const StepOptions& o, double h, int depth) {
  StepResult out;
  if (try_step(ws, state, body, body_end, pin_targets, o, h, out)) return out;
  if (depth >= 8) {
    throw SolverError(fmt::format(
        "simulation: at t = {:.4f} s the body moves through the fabric even in steps of {:.3g} s; slow the motion, "
        "or start the fabric farther from the body",
        state.time_s, h));
  }
  // Halve: the body and the pins at the middle of their motion.
  std::vector<Vec3> body_mid, pins_mid;
  for (size_t k = 0; k < body_end.size(); ++k) body_mid.push_back(0.5 * (body.mesh().vertices[k] + body_end[k]));
  const SimModel& model = ws.model();
  for (size_t k = 0; k < pin_targets.size(); ++k)
    pins_mid.push_back(0.5 * (Vec3(state.positions_mm.segment<3>(3 * model.pinned[k])) + pin_targets[k]));
  StepResult first = step_recursive(ws, state, body, body_mid, pins_mid, o, 0.5 * h, depth + 1);
  KinematicBody mid = body;
  mid.move_to(body_mid);
  StepResult second = step_recursive(ws, first.state, mid, body_end, pin_targets, o, 0.5 * h, depth + 1);
  second.converged = second.converged && first.converged;
  second.newton_iterations += first.newton_iterations;
  second.quasi_newton_iterations += first.quasi_newton_iterations;
  second.factorizations += first.factorizations;
  second.solves_at_iteration_limit += first.solves_at_iteration_limit;
  second.substeps += first.substeps;
  accumulate(second.seconds, first.seconds);
  return second;
}

}  // namespace

StepResult step_simulation(SimWorkspace& ws, const SimState& state, const KinematicBody& body,
                           const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets,
                           const StepOptions& options) {
  const SimModel& model = ws.model();
  const Eigen::Index n3 = 3 * static_cast<Eigen::Index>(model.num_vertices());
  if (state.positions_mm.size() != n3 || state.velocities_mm_s.size() != n3) {
    throw InvalidInput(fmt::format("simulation: the state has {} positions and {} velocities for {} unknowns",
                                   state.positions_mm.size(), state.velocities_mm_s.size(), n3));
  }
  if (!(options.time_step_s > 0 && std::isfinite(options.time_step_s))) {
    throw InvalidInput(fmt::format("simulation: the time step {} s must be positive", options.time_step_s));
  }
  if (!options.gravity_mm_s2.allFinite()) throw InvalidInput("simulation: gravity is not finite");
  check_contact(options.contact);
  if (!body_end.empty() && body_end.size() != body.mesh().vertices.size()) {
    throw InvalidInput(fmt::format("simulation: the body's next pose has {} vertices, the body {}", body_end.size(),
                                   body.mesh().vertices.size()));
  }
  if (!pin_targets.empty() && pin_targets.size() != model.pinned.size()) {
    throw InvalidInput(fmt::format("simulation: {} pin targets for {} pinned vertices", pin_targets.size(),
                                   model.pinned.size()));
  }
  StepResult r = step_recursive(ws, state, body, body_end, pin_targets, options, options.time_step_s, 0);
  r.energy = elastic_energy(model, r.state.positions_mm);
  return r;
}

EquilibriumResult solve_equilibrium(SimWorkspace& ws, const Eigen::VectorXd& x0, const KinematicBody* support,
                                    const EquilibriumOptions& o) {
  const SimModel& model = ws.model();
  if (x0.size() != 3 * static_cast<Eigen::Index>(model.num_vertices())) {
    throw InvalidInput(fmt::format("equilibrium: {} start coordinates for {} vertices", x0.size(), model.num_vertices()));
  }
  if (!o.gravity_mm_s2.allFinite()) throw InvalidInput("equilibrium: gravity is not finite");
  check_contact(o.contact);
  if (!(o.friction_slip_mm > 0)) throw InvalidInput("equilibrium: friction_slip_mm must be positive");
  const bool has_body = support && !support->empty();
  if (o.gravity_mm_s2.norm() > 0 && !has_body && model.pinned.empty()) {
    throw InvalidInput(
        "equilibrium: under gravity a piece that is neither supported nor pinned falls and has no equilibrium; "
        "give a support (e.g. predict --on SUPPORT.obj) or pins, or switch gravity off");
  }
  if (has_body) {
    const double d = min_distance_to_body(*support, x0, o.contact.distance_mm, ws.pinned_vertices());
    if (!(d > 0)) {
      throw InvalidInput(
          "equilibrium: the fabric touches the support at the start (distance 0); start it a little away from the "
          "support (a gap)");
    }
  }
  std::vector<char> fixed = ws.fixed_dofs();
  if (!o.held_coordinates.empty()) {
    if (o.held_coordinates.size() != fixed.size()) {
      throw InvalidInput(fmt::format("equilibrium: {} held-coordinate flags for {} coordinates",
                                     o.held_coordinates.size(), fixed.size()));
    }
    for (size_t k = 0; k < fixed.size(); ++k) fixed[k] = fixed[k] || o.held_coordinates[k];
  }
  const double dhat = o.contact.distance_mm;
  ContactParams fp = o.contact;
  fp.friction_velocity_mm_s = o.friction_slip_mm;  // with h = 1: ε = the slip
  EquilibriumResult out;
  Eigen::VectorXd x = x0;
  out.converged = true;
  const int rounds = has_body && o.contact.friction > 0 ? std::max(1, o.friction_iterations) : 1;
  for (int fi = 0; fi < rounds; ++fi) {
    std::vector<FrictionPair> friction;
    if (has_body && o.contact.friction > 0) {
      // Normal forces of the start (round 0) or of the last solution; the
      // slip is measured from the start.
      const std::vector<ContactPair> c = find_contact_candidates(*support, x, dhat, ws.pinned_vertices());
      friction = build_friction_pairs(model, c, *support, *support, x, fp);
    }
    // The energy with the element Hessians projected by `projection`.
    auto energy = [&](PsdProjection projection) {
      return [&, projection](const Eigen::VectorXd& y, Derivatives what) {
        EnergyEval ev(model.num_vertices(), what, what == Derivatives::Hessian ? ws.pattern() : nullptr);
        add_membrane_energy(model, y, projection, ev);
        add_bending_energy(model, y, ev, projection);
        if (o.gravity_mm_s2.norm() > 0) add_gravity_energy(model, y, o.gravity_mm_s2, ev);
        if (has_body) {
          const std::vector<ContactPair> pairs = find_contact_candidates(*support, y, dhat, ws.pinned_vertices());
          add_contact_energy(model, pairs, *support, y, o.contact, ev);
          if (std::isfinite(ev.value)) add_friction_energy(friction, y, x0, 1.0, fp, ev);
        }
        return ev;
      };
    };
    const MaxStep max_step = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
      return has_body ? collision_free_step(*support, a, b, ws.pinned_vertices()) : 1.0;
    };
    if (o.quasi_newton.max_iterations > 0) {
      QuasiNewtonOptions qo = o.quasi_newton;
      qo.force_tolerance_mn = o.newton.force_tolerance_mn;
      const QuasiNewtonResult q =
          quasi_newton_solve(x, fixed, energy(o.projection), energy(PsdProjection::Clamp), max_step, qo, ws.solver());
      x = q.x;
      out.quasi_newton_iterations += q.iterations;
      out.quasi_newton_evaluations += q.evaluations;
      out.factorizations += q.factorizations;
      accumulate(out.seconds, q.seconds);
    }
    const bool projected_start = o.projection == PsdProjection::None && o.start_projection != PsdProjection::None;
    const NewtonResult r = newton_solve(x, fixed, energy(o.projection), max_step, o.newton, ws.solver(),
                                        projected_start ? EvaluateEnergy(energy(o.start_projection)) : EvaluateEnergy{});
    x = r.x;
    if (fi == rounds - 1 && r.converged) {
      // Is it a minimum? The exact Hessian factors only when positive definite.
      const Timer t;
      EnergyEval h = energy(PsdProjection::None)(x, Derivatives::Hessian);
      hold_fixed_unknowns(*h.pattern, fixed, h.hessian_values);
      try {
        ws.solver().refactor(h.pattern->matrix(h.hessian_values));
        out.local_minimum = true;
      } catch (const SolverError&) {
      }
      out.seconds.factor += t.seconds();
    }
    out.converged = r.converged;  // the last round decides
    out.iterations += r.iterations;
    out.factorizations += r.factorizations;
    out.max_force_mn = r.max_force_mn;
    out.stop_reason = r.stop_reason;
    accumulate(out.seconds, r.seconds);
    out.history.insert(out.history.end(), r.history.begin(), r.history.end());
  }
  out.positions_mm = x;
  out.energy = elastic_energy(model, x);
  if (has_body) {
    out.contacts = static_cast<int>(find_contact_candidates(*support, x, dhat, ws.pinned_vertices()).size());
    out.min_distance_mm = min_distance_to_body(*support, x, dhat, ws.pinned_vertices());
  } else {
    out.min_distance_mm = std::numeric_limits<double>::infinity();
  }
  return out;
}

}  // namespace knitforge
