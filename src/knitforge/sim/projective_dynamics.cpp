#include "knitforge/sim/projective_dynamics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/core.h>

#include "knitforge/sim/collision_free_step.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/parallel_ranges.h"
#include "knitforge/util/timer.h"

namespace knitforge {

namespace {

// The rest corners of an element in its material frame: P0 = 0, then the
// columns of the rest-shape matrix (the inverse of rest_inverse).
std::array<Vec2, 3> rest_corners(const MembraneElement& el) {
  const Mat2 D = el.rest_inverse.inverse();
  return {Vec2::Zero(), Vec2(D.col(0)), Vec2(D.col(1))};
}

int corner_of(const MembraneElement& el, int vertex) {
  for (int k = 0; k < 3; ++k)
    if (el.v[k] == vertex) return k;
  return -1;
}

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The position along the edge (from its first vertex) and the height of the
// third vertex `third` of element `el` over its edge (e0, e1), and the
// edge's rest length.
struct HingeSide {
  double along = 0.0, height = 0.0, edge = 0.0;
};
HingeSide hinge_side(const MembraneElement& el, int e0, int e1, int third) {
  const auto P = rest_corners(el);
  const Vec2 q0 = P[corner_of(el, e0)], q1 = P[corner_of(el, e1)], q2 = P[corner_of(el, third)];
  const Vec2 e = q1 - q0;
  HingeSide s;
  s.edge = e.norm();
  if (!(s.edge > 0)) return s;
  s.along = (q2 - q0).dot(e) / s.edge;
  s.height = std::abs(cross2(e, q2 - q0)) / s.edge;
  return s;
}

// A vertex's half-space against one body part for the step: the tangent
// plane at its closest point at the start, carried to the end pose.
struct Anchor {
  int vertex = -1;
  Vec3 point = Vec3::Zero();   // the plane's point at the end (mm)
  Vec3 normal = Vec3::Zero();  // unit, towards the side the vertex starts on
  Vec3 motion = Vec3::Zero();  // the body point's motion over the step (mm)
  bool active = false;         // in the system matrix this step
};

// The target of an anchor's term at x: out along the normal by the depth,
// the tangential motion relative to the body taken back up to μ x depth.
Vec3 anchor_target(const Anchor& a, const Vec3& x, const Vec3& x_start, double dhat, double mu) {
  const double height = a.normal.dot(x - a.point);
  if (height >= dhat) return x;
  const double depth = dhat - height;
  const Vec3 u = (x - x_start) - a.motion;
  const Vec3 ut = u - a.normal.dot(u) * a.normal;
  const double slip = ut.norm();
  Vec3 t = x + depth * a.normal;
  if (slip <= mu * depth) {
    t -= ut;
  } else if (slip > 0) {
    t -= (mu * depth / slip) * ut;
  }
  return t;
}

void check_step_inputs(const PreviewWorkspace& ws, const SimState& state, const KinematicBody& body,
                       const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets, double h,
                       double dhat, double mu, const PreviewOptions& o) {
  const auto n3 = 3 * static_cast<Eigen::Index>(ws.model->num_vertices());
  if (state.positions_mm.size() != n3 || state.velocities_mm_s.size() != n3) {
    throw InvalidInput(fmt::format("preview step: the state has {} positions and {} velocities for {} coordinates",
                                   state.positions_mm.size(), state.velocities_mm_s.size(), n3));
  }
  if (!pin_targets.empty() && pin_targets.size() != ws.model->pinned.size()) {
    throw InvalidInput(fmt::format("preview step: {} pin targets for {} pinned vertices", pin_targets.size(),
                                   ws.model->pinned.size()));
  }
  if (!body_end.empty() && body_end.size() != body.mesh().vertices.size()) {
    throw InvalidInput(fmt::format("preview step: the body's end pose has {} vertices, the body {}", body_end.size(),
                                   body.mesh().vertices.size()));
  }
  if (!(h > 0) || !std::isfinite(h) || !(dhat > 0) || !std::isfinite(dhat) || !(mu >= 0) || !std::isfinite(mu)) {
    throw InvalidInput(fmt::format(
        "preview step: the time step {} s and contact distance {} mm must be positive, the friction {} >= 0", h, dhat,
        mu));
  }
  if (o.max_iterations < 1 || !(o.tolerance_mm > 0) || !(o.contact_weight_factor > 0)) {
    throw InvalidInput(fmt::format(
        "preview step: iterations {} must be >= 1, the tolerance {} mm and contact weight factor {} positive",
        o.max_iterations, o.tolerance_mm, o.contact_weight_factor));
  }
}

}  // namespace

std::vector<PreviewRow> build_preview_rows(const SimModel& model) {
  const int ne = model.num_elements();
  std::vector<PreviewRow> rows(2 * static_cast<size_t>(ne) + model.hinges.size());
  for (int e = 0; e < ne; ++e) {
    const MembraneElement& el = model.elements[e];
    const Mat2& R = el.rest_inverse;
    rows[2 * e] = {{el.v[0], el.v[1], el.v[2], -1}, {-(R(0, 0) + R(1, 0)), R(0, 0), R(1, 0), 0.0}};
    rows[2 * e + 1] = {{el.v[0], el.v[1], el.v[2], -1}, {-(R(0, 1) + R(1, 1)), R(0, 1), R(1, 1), 0.0}};
  }
  for (size_t k = 0; k < model.hinges.size(); ++k) {
    const BendingHinge& hg = model.hinges[k];
    const auto [with2, with3] = hg.elements;
    if (with2 < 0 || with3 < 0 || with2 >= ne || with3 >= ne) {
      throw InvalidInput(fmt::format("preview: hinge {} (edge {}-{}) does not join two elements of the model", k,
                                     hg.v[0], hg.v[1]));
    }
    const HingeSide s2 = hinge_side(model.elements[with2], hg.v[0], hg.v[1], hg.v[2]);
    const HingeSide s3 = hinge_side(model.elements[with3], hg.v[0], hg.v[1], hg.v[3]);
    if (!(s2.height > 1e-9 * s2.edge) || !(s3.height > 1e-9 * s3.edge)) {
      throw InvalidInput(fmt::format("preview: hinge {} (edge {}-{}) has a degenerate rest triangle", k, hg.v[0],
                                     hg.v[1]));
    }
    // The affine dependency of the four points unfolded into one plane (the
    // second triangle's position along the edge scaled to the first's edge
    // length where the two rest shapes disagree).
    const double L = s2.edge;
    const double a2 = 1.0 / s2.height, a3 = 1.0 / s3.height;
    const double a1 = -(s2.along * a2 + s3.along * (L / s3.edge) * a3) / L;
    const double a0 = -(a1 + a2 + a3);
    rows[2 * static_cast<size_t>(ne) + k] = {{hg.v[0], hg.v[1], hg.v[2], hg.v[3]}, {a0, a1, a2, a3}};
  }
  return rows;
}

FiberSpring fiber_spring(const TensionCurve& curve, double strain) {
  const CurveValue cv = evaluate_curve(curve, strain);
  FiberSpring s;
  s.stiffness_n_per_m = cv.slope;
  s.rest_strain = cv.slope > 0 ? strain - cv.tension / cv.slope : 0.0;
  return s;
}

std::pair<Vec3, Vec3> project_perpendicular_pair(const Vec3& a, const Vec3& b) {
  const double c = a.dot(b), s = a.squaredNorm() + b.squaredNorm();
  if (c == 0.0) return {a, b};
  // The smaller root of c λ² - s λ + c = 0, in the form without cancellation.
  const double lambda = 2.0 * c / (s + std::sqrt(std::max(0.0, s * s - 4.0 * c * c)));
  const double d = 1.0 - lambda * lambda;
  if (!(d > 1e-12)) return {a, b};  // a = ±b: no nearest pair
  return {(a - lambda * b) / d, (b - lambda * a) / d};
}

PreviewWorkspace::PreviewWorkspace(const SimModel& m) : model(&m), rows(build_preview_rows(m)) {
  const int n = m.num_vertices();
  pinned.assign(n, 0);
  for (int v : m.pinned) {
    if (v < 0 || v >= n) throw InvalidInput(fmt::format("preview: pinned vertex {} out of range (0..{})", v, n - 1));
    pinned[v] = 1;
  }
  free_index.assign(n, -1);
  for (int v = 0; v < n; ++v) {
    if (pinned[v]) continue;
    free_index[v] = static_cast<int>(free_vertex.size());
    free_vertex.push_back(v);
  }
  const int nf = static_cast<int>(free_vertex.size());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(nf + 10 * rows.size());
  for (int i = 0; i < nf; ++i) entries.emplace_back(i, i, 0.0);
  for (const PreviewRow& r : rows) {
    for (int a = 0; a < 4; ++a) {
      for (int b = a; b < 4; ++b) {
        if (r.v[a] < 0 || r.v[b] < 0) continue;
        const int i = free_index[r.v[a]], j = free_index[r.v[b]];
        if (i < 0 || j < 0) continue;
        entries.emplace_back(std::max(i, j), std::min(i, j), 0.0);
      }
    }
  }
  matrix.resize(nf, nf);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  auto slot = [&](int i, int j) {
    const int row = std::max(i, j), col = std::min(i, j);
    const int* inner = matrix.innerIndexPtr();
    const int* begin = inner + matrix.outerIndexPtr()[col];
    const int* end = inner + matrix.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - inner);
  };
  diagonal_slot.resize(nf);
  for (int i = 0; i < nf; ++i) diagonal_slot[i] = slot(i, i);
  row_slots.resize(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const PreviewRow& r = rows[k];
    int q = 0;
    for (int a = 0; a < 4; ++a) {
      for (int b = a; b < 4; ++b, ++q) {
        const int i = r.v[a] < 0 ? -1 : free_index[r.v[a]], j = r.v[b] < 0 ? -1 : free_index[r.v[b]];
        row_slots[k][q] = (i < 0 || j < 0) ? -1 : slot(i, j);
      }
    }
  }
  if (nf > 0) solver.analyze(matrix);
}

namespace {

// One step without splitting; nullopt when the body moves and the
// simultaneous motion of body and fabric is not collision free (a vertex
// held back would then be left inside the body's end pose).
std::optional<PreviewStepResult> try_preview_step(PreviewWorkspace& ws, const SimState& state,
                                                  const KinematicBody& body, const std::vector<Vec3>& body_end,
                                                  const std::vector<Vec3>& pin_targets, double h, const Vec3& gravity,
                                                  double dhat, double mu, const PreviewOptions& o) {
  const SimModel& model = *ws.model;
  const int n = model.num_vertices(), ne = model.num_elements(), nf = static_cast<int>(ws.free_vertex.size());
  const size_t nrows = ws.rows.size();
  const Eigen::VectorXd& xn = state.positions_mm;
  const Eigen::VectorXd& vn = state.velocities_mm_s;
  PreviewStepResult out;

  // The positions: free vertices from their inertial guess, pins at their targets.
  Eigen::VectorXd x = xn + h * vn;
  for (size_t k = 0; k < model.pinned.size(); ++k) {
    const int v = model.pinned[k];
    x.segment<3>(3 * v) = pin_targets.empty() ? Vec3(xn.segment<3>(3 * v)) : pin_targets[k];
  }
  auto pos = [&](const Eigen::VectorXd& y, int v) -> Vec3 { return y.segment<3>(3 * v); };
  auto combine = [&](const Eigen::VectorXd& y, const PreviewRow& r) {
    Vec3 s = Vec3::Zero();
    for (int a = 0; a < 4; ++a)
      if (r.v[a] >= 0) s += r.c[a] * pos(y, r.v[a]);
    return s;
  };

  // Weights: the tension segments at the step's start, shear, bending.
  Timer factor_timer;
  std::vector<double> weight(nrows), fiber_weight(2 * static_cast<size_t>(ne)), rest_length(2 * static_cast<size_t>(ne));
  std::vector<double> shear_weight(ne);
  for (int e = 0; e < ne; ++e) {
    const MembraneElement& el = model.elements[e];
    const KnitMaterial& mat = model.materials[el.material];
    const double A = el.rest_area_mm2;
    shear_weight[e] = 2.0 * A * mat.shear.initial_stiffness();
    for (int d = 0; d < 2; ++d) {
      const size_t r = 2 * static_cast<size_t>(e) + d;
      const double strain = combine(xn, ws.rows[r]).norm() - 1.0;
      const FiberSpring s = fiber_spring(d == 0 ? mat.course : mat.wale, strain);
      fiber_weight[r] = A * s.stiffness_n_per_m;
      rest_length[r] = std::max(1e-3, 1.0 + s.rest_strain);
      weight[r] = fiber_weight[r] + shear_weight[e];
    }
  }
  for (size_t k = 0; k < model.hinges.size(); ++k) weight[2 * static_cast<size_t>(ne) + k] = 2.0 * model.hinges[k].stiffness;

  // The system matrix without contacts, and the inertia's right-hand side.
  double* values = ws.matrix.valuePtr();
  std::fill(values, values + ws.matrix.nonZeros(), 0.0);
  Eigen::MatrixXd inertia_rhs(nf, 3);
  for (int i = 0; i < nf; ++i) {
    const int v = ws.free_vertex[i];
    const double m = model.vertex_mass_kg[v], c = model.vertex_damping_kg_s[v];
    values[ws.diagonal_slot[i]] += m / (h * h) + c / h;
    const Vec3 r = m / (h * h) * (pos(xn, v) + h * Vec3(vn.segment<3>(3 * v))) + c / h * pos(xn, v) + m * gravity;
    inertia_rhs.row(i) = r.transpose();
  }
  for (size_t k = 0; k < nrows; ++k) {
    const PreviewRow& r = ws.rows[k];
    int q = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b, ++q)
        if (ws.row_slots[k][q] >= 0) values[ws.row_slots[k][q]] += weight[k] * r.c[a] * r.c[b];
  }
  out.factor_seconds += factor_timer.seconds();

  // Contacts: every free vertex within reach of the body at the start gets a
  // half-space per part it is near.
  Timer contact_timer;
  std::vector<Anchor> anchors;
  KinematicBody end_body = body;
  if (!body.empty()) {
    if (!body_end.empty()) end_body.move_to(body_end);
    double body_speed = 0.0;
    for (size_t k = 0; k < body_end.size(); ++k)
      body_speed = std::max(body_speed, (body_end[k] - body.mesh().vertices[k]).norm());
    std::vector<std::vector<Anchor>> found(n);
    parallel_ranges(static_cast<size_t>(n), 256, [&](size_t begin, size_t end) {
      for (size_t vv = begin; vv < end; ++vv) {
        const int v = static_cast<int>(vv);
        if (ws.pinned[v]) continue;
        const Vec3 p = pos(xn, v);
        // The vertex's own motion: its inertial guess's, twice.
        const double own = 2.0 * (h * Vec3(vn.segment<3>(3 * v)) + h * h * gravity).norm();
        const double reach = dhat + 2.0 * body_speed + own + 1.0;
        for (const BodyPoint& q : body.closest_points_per_part_within(p, reach)) {
          const Vec3 face_n = body.face_normal(q.face);
          if (!(face_n.norm() > 0)) continue;
          const Vec3 d = p - q.where.point;
          const double dist = d.norm();
          Vec3 normal = dist > 1e-9 ? Vec3(d / dist) : face_n;
          if (dist <= 1e-9 && !(face_n.dot(d) >= 0)) normal = -face_n;
          Anchor a;
          a.vertex = v;
          const Vec3 end_point = end_body.point(q.face, q.where.bary);
          a.motion = end_point - q.where.point;
          a.normal = face_frame(end_body.mesh(), end_body.mesh().vertices, q.face) *
                     (face_frame(body.mesh(), body.mesh().vertices, q.face).transpose() * normal);
          if (!a.normal.allFinite()) a.normal = normal;  // the face degenerates at the end pose: keep its start normal
          a.point = end_point;
          found[v].push_back(a);
        }
      }
    });
    for (auto& f : found) anchors.insert(anchors.end(), f.begin(), f.end());
  }
  // The terms in the matrix: the anchors the vertex touches, at its start or
  // at its inertial guess.
  std::vector<double> contact_weight(nf, 0.0);
  for (Anchor& a : anchors) {
    const double margin = 0.5 * dhat;
    a.active = a.normal.dot(pos(xn, a.vertex) + a.motion - a.point) < dhat + margin ||
               a.normal.dot(pos(x, a.vertex) - a.point) < dhat + margin;
    if (!a.active) continue;
    const int i = ws.free_index[a.vertex];
    contact_weight[i] = o.contact_weight_factor * values[ws.diagonal_slot[i]];
  }
  for (const Anchor& a : anchors)
    if (a.active) values[ws.diagonal_slot[ws.free_index[a.vertex]]] += contact_weight[ws.free_index[a.vertex]];
  out.contacts = static_cast<int>(anchors.size());
  out.contact_seconds += contact_timer.seconds();

  factor_timer.reset();
  if (nf > 0) ws.solver.refactor(ws.matrix);
  out.factor_seconds += factor_timer.seconds();

  // The rows' pinned parts, fixed over the step: Σ over pinned vertices c x.
  std::vector<Vec3> pinned_part(nrows, Vec3::Zero());
  if (!model.pinned.empty()) {
    for (size_t k = 0; k < nrows; ++k) {
      const PreviewRow& r = ws.rows[k];
      for (int a = 0; a < 4; ++a)
        if (r.v[a] >= 0 && ws.pinned[r.v[a]]) pinned_part[k] += r.c[a] * pos(x, r.v[a]);
    }
  }

  // Local-global rounds.
  Timer iterate_timer;
  std::vector<Vec3> target(2 * static_cast<size_t>(ne));  // weighted: w_fiber p + w_shear s
  Eigen::MatrixXd rhs(nf, 3);
  for (int it = 0; it < o.max_iterations && nf > 0; ++it) {
    parallel_ranges(static_cast<size_t>(ne), 2048, [&](size_t begin, size_t end) {
      for (size_t e = begin; e < end; ++e) {
        const Vec3 a = combine(x, ws.rows[2 * e]), b = combine(x, ws.rows[2 * e + 1]);
        const auto [sa, sb] = project_perpendicular_pair(a, b);
        const double la = a.norm(), lb = b.norm();
        const Vec3 pa = la > 0 ? Vec3(a * (rest_length[2 * e] / la)) : a;
        const Vec3 pb = lb > 0 ? Vec3(b * (rest_length[2 * e + 1] / lb)) : b;
        target[2 * e] = fiber_weight[2 * e] * pa + shear_weight[e] * sa;
        target[2 * e + 1] = fiber_weight[2 * e + 1] * pb + shear_weight[e] * sb;
      }
    });
    rhs = inertia_rhs;
    for (size_t k = 0; k < nrows; ++k) {
      const PreviewRow& r = ws.rows[k];
      const Vec3 q = (k < target.size() ? target[k] : Vec3::Zero()) - weight[k] * pinned_part[k];
      for (int a = 0; a < 4; ++a) {
        if (r.v[a] < 0) continue;
        const int i = ws.free_index[r.v[a]];
        if (i >= 0) rhs.row(i) += r.c[a] * q.transpose();
      }
    }
    for (const Anchor& a : anchors) {
      if (!a.active) continue;
      const int i = ws.free_index[a.vertex];
      rhs.row(i) += contact_weight[i] * anchor_target(a, pos(x, a.vertex), pos(xn, a.vertex), dhat, mu).transpose();
    }
    const Eigen::MatrixXd solved = ws.solver.solve_columns(rhs);
    double move = 0.0;
    for (int i = 0; i < nf; ++i) {
      const int v = ws.free_vertex[i];
      const Vec3 next = solved.row(i).transpose();
      move = std::max(move, (next - pos(x, v)).norm());
      x.segment<3>(3 * v) = next;
    }
    out.iterations = it + 1;
    out.last_move_mm = move;
    if (!std::isfinite(move)) throw SolverError("preview step: the positions became non-finite");
    if (move <= o.tolerance_mm) {
      out.converged = true;
      break;
    }
  }
  if (nf == 0) out.converged = true;
  out.iterate_seconds = iterate_timer.seconds();

  // Every vertex onto its half-spaces (alternating projections).
  contact_timer.reset();
  for (int round = 0; round < 4; ++round) {
    bool moved = false;
    for (const Anchor& a : anchors) {
      const double height = a.normal.dot(pos(x, a.vertex) - a.point);
      if (height < dhat) {
        x.segment<3>(3 * a.vertex) += (dhat - height) * a.normal;
        moved = true;
      }
    }
    if (!moved) break;
  }
  // No vertex passes through the body (continuous collision detection, as
  // the implicit solver's steps): against a body that stays, each vertex
  // keeps the collision-free fraction of its move; against a moving one,
  // the step is refused (and split by the caller).
  if (!body.empty()) {
    std::vector<double> fraction;
    const double t =
        collision_free_step(body, body_end.empty() ? body.mesh().vertices : body_end, xn, x, ws.pinned, &fraction);
    if (t < 1.0 && !body_end.empty()) return std::nullopt;
    for (int v = 0; v < n && t < 1.0; ++v) {
      if (fraction[v] >= 1.0) continue;
      x.segment<3>(3 * v) = xn.segment<3>(3 * v) + fraction[v] * (x.segment<3>(3 * v) - xn.segment<3>(3 * v));
      ++out.held_back;
    }
  }
  out.min_distance_mm = body.empty() ? std::numeric_limits<double>::infinity()
                                     : min_distance_to_body(end_body, x, dhat + 1.0, ws.pinned);
  out.contact_seconds += contact_timer.seconds();

  out.state.positions_mm = x;
  out.state.velocities_mm_s = (x - xn) / h;
  out.state.time_s = state.time_s + h;
  return out;
}

// The step, split in halves (body poses and pin targets halfway) while the
// body's motion would pass through the fabric, up to 8 levels.
PreviewStepResult advance(PreviewWorkspace& ws, const SimState& state, const KinematicBody& body,
                          const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets, double h,
                          const Vec3& gravity, double dhat, double mu, const PreviewOptions& o, int level) {
  if (auto r = try_preview_step(ws, state, body, body_end, pin_targets, h, gravity, dhat, mu, o)) return *r;
  if (level >= 8) {
    throw SolverError(fmt::format("preview step: the body moves through the fabric even in steps of {:.3g} s", h));
  }
  std::vector<Vec3> mid(body_end.size()), mid_pins(pin_targets.size());
  for (size_t k = 0; k < body_end.size(); ++k) mid[k] = 0.5 * (body.mesh().vertices[k] + body_end[k]);
  for (size_t k = 0; k < pin_targets.size(); ++k)
    mid_pins[k] = 0.5 * (Vec3(state.positions_mm.segment<3>(3 * ws.model->pinned[k])) + pin_targets[k]);
  PreviewStepResult a = advance(ws, state, body, mid, mid_pins, 0.5 * h, gravity, dhat, mu, o, level + 1);
  KinematicBody halfway = body;
  halfway.move_to(mid);
  PreviewStepResult b = advance(ws, a.state, halfway, body_end, pin_targets, 0.5 * h, gravity, dhat, mu, o, level + 1);
  b.converged = a.converged && b.converged;
  b.iterations += a.iterations;
  b.held_back += a.held_back;
  b.substeps += a.substeps;
  b.last_move_mm = std::max(a.last_move_mm, b.last_move_mm);
  b.min_distance_mm = std::min(a.min_distance_mm, b.min_distance_mm);
  b.factor_seconds += a.factor_seconds;
  b.iterate_seconds += a.iterate_seconds;
  b.contact_seconds += a.contact_seconds;
  return b;
}

}  // namespace

PreviewStepResult preview_step(PreviewWorkspace& ws, const SimState& state, const KinematicBody& body,
                               const std::vector<Vec3>& body_end, const std::vector<Vec3>& pin_targets, double h,
                               const Vec3& gravity, double dhat, double mu, const PreviewOptions& o) {
  check_step_inputs(ws, state, body, body_end, pin_targets, h, dhat, mu, o);
  return advance(ws, state, body, body_end, pin_targets, h, gravity, dhat, mu, o, 0);
}

}  // namespace knitforge
