#include "knitforge/sim/simulate_cloth.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/core.h>

#include "knitforge/sim/body_sliding.h"
#include "knitforge/sim/collision_free_step.h"
#include "knitforge/sim/dress_garment.h"
#include "knitforge/sim/kinematic_body.h"
#include "knitforge/sim/membrane_energy.h"
#include "knitforge/sim/step_simulation.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"
#include "knitforge/util/work_limit.h"

namespace knitforge {

namespace {

// A vertex riding on the body: its face, barycentrics and offset in the
// face's frame.
struct Attachment {
  int face = -1;
  Vec3 bary = Vec3::Zero();
  Vec3 local = Vec3::Zero();
};

Vec3 face_point(const TriMesh& mesh, const std::vector<Vec3>& pos, int face, const Vec3& b) {
  const auto& t = mesh.faces[face];
  return b[0] * pos[t[0]] + b[1] * pos[t[1]] + b[2] * pos[t[2]];
}

void add(NewtonTimings& a, const NewtonTimings& b) {
  a.evaluate += b.evaluate;
  a.factor += b.factor;
  a.max_step += b.max_step;
  a.line_search += b.line_search;
}

void check_options(const ClothOptions& o) {
  if (o.frames < 1 || o.substeps < 1 || !(o.frame_rate_hz > 0) || !std::isfinite(o.frame_rate_hz)) {
    throw InvalidInput(fmt::format("cloth: frames {} and substeps {} must be >= 1, the frame rate {} Hz positive",
                                   o.frames, o.substeps, o.frame_rate_hz));
  }
  if (!(o.sliding_distance_mm > 0) || !(o.distance_range_mm > 0)) {
    throw InvalidInput("cloth: the sliding distance and the distance range must be positive");
  }
}

}  // namespace

void check_cloth_work(int vertices, int frames, int substeps, double limit, int preview_rounds) {
  const double steps = static_cast<double>(vertices) * frames * substeps;
  const double scale = std::max(1.0, preview_rounds / 30.0);
  // positions, velocities, stress and sliding kept per frame, over the steps of a frame
  const double bytes = 64.0 / std::max(1, substeps) / scale;
  if (preview_rounds > 0) {
    check_work({"the preview (garment vertices x frames x substeps x rounds / 30)", steps * scale, "vertex-steps",
                limit, bytes,
                "use fewer frames, substeps or --preview-iterations or a coarser garment, or raise the limit with "
                "--max-work N"});
  } else {
    check_work({"the cloth run (garment vertices x frames x substeps)", steps, "vertex-steps", limit, bytes,
                "use fewer frames or substeps or a coarser garment (or --preview), or raise the limit with "
                "--max-work N"});
  }
}

ClothResult simulate_cloth(const SimModel& model, const TriMesh& body_mesh,
                           const std::vector<std::vector<Vec3>>& body_frames, const std::vector<int>& attached,
                           const ClothOptions& o, const std::function<void(const ClothFrame&)>& on_frame) {
  check_options(o);
  if (!body_frames.empty() && static_cast<int>(body_frames.size()) != o.frames + 1) {
    throw InvalidInput(fmt::format("cloth: {} body poses for {} frames (frames + 1 = {} needed)", body_frames.size(),
                                   o.frames, o.frames + 1));
  }
  for (const auto& pose : body_frames) {
    if (pose.size() != body_mesh.vertices.size()) {
      throw InvalidInput(fmt::format("cloth: a body pose has {} vertices, the body mesh {} (every frame needs the "
                                     "same mesh)",
                                     pose.size(), body_mesh.vertices.size()));
    }
  }
  const int n = model.num_vertices(), ne = model.num_elements();
  KinematicBody body(body_mesh);
  if (!body_frames.empty()) body.move_to(body_frames[0]);
  const bool preview = o.solver == ClothSolver::Preview;
  std::optional<SimWorkspace> ws;
  std::optional<PreviewWorkspace> pws;
  if (preview) {
    pws.emplace(model);
  } else {
    ws.emplace(model);
  }
  const std::vector<char>& pinned = preview ? pws->pinned : ws->pinned_vertices();

  // Attachments from the start pose.
  std::vector<Attachment> att(model.pinned.size());
  std::vector<char> is_attached(model.pinned.size(), 0);
  for (int v : attached) {
    const auto it = std::lower_bound(model.pinned.begin(), model.pinned.end(), v);
    if (it == model.pinned.end() || *it != v) {
      throw InvalidInput(fmt::format("cloth: attached vertex {} is not among the model's pinned vertices", v));
    }
    const size_t k = static_cast<size_t>(it - model.pinned.begin());
    const auto q = body.closest_point_within(model.rest_positions[v], std::numeric_limits<double>::max());
    if (!q) throw InvalidInput(fmt::format("cloth: attached vertex {} finds no body point", v));
    if (!(body.face_normal(q->face).norm() > 0)) {
      throw InvalidInput(fmt::format("cloth: attached vertex {} is closest to the degenerate body face {}", v, q->face));
    }
    att[k] = {q->face, q->where.bary,
              face_frame(body.mesh(), body.mesh().vertices, q->face).transpose() *
                  (model.rest_positions[v] - q->where.point)};
    is_attached[k] = 1;
  }

  SimState state;
  state.positions_mm.resize(3 * static_cast<Eigen::Index>(n));
  for (int v = 0; v < n; ++v) state.positions_mm.segment<3>(3 * v) = model.rest_positions[v];
  state.velocities_mm_s = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(n));
  {
    const double d = min_distance_to_body(body, state.positions_mm, o.contact.distance_mm, pinned);
    if (!(d > 0)) {
      throw InvalidInput(
          "cloth: a free garment vertex touches the body at the start (distance 0); start the garment a little "
          "away from the body (a clearance: dress_garment(), the scene's garment.clearance_mm), or attach or pin "
          "that vertex");
    }
    // A closed body has an inside; fabric there would stay there (the
    // barrier keeps every vertex on its side).
    const std::vector<InsidePoint> inside = points_inside_body(body, model.rest_positions, model.pinned);
    if (!inside.empty()) {
      throw InvalidInput(fmt::format(
          "cloth: {} free garment vertices start inside the body (vertex {} the deepest, {:.2f} mm); dress the "
          "garment (dress_garment(), the scene's garment.clearance_mm) or place it around the body",
          inside.size(), inside.front().vertex, inside.front().depth_mm));
    }
  }

  StepOptions so;
  so.time_step_s = 1.0 / (o.frame_rate_hz * o.substeps);
  so.gravity_mm_s2 = o.gravity_mm_s2;
  so.contact = o.contact;
  so.newton = o.newton;
  so.projection = o.projection;
  so.quasi_newton = o.quasi_newton;

  ClothResult result;
  result.max_stress_kpa.assign(ne, 0.0);
  result.min_distance_mm = std::numeric_limits<double>::infinity();
  BodySliding sliding = start_body_sliding(n);

  auto measure = [&](ClothFrame& fr) {
    const Timer t;
    const Eigen::VectorXd& x = state.positions_mm;
    fr.time_s = state.time_s;
    fr.positions.resize(n);
    for (int v = 0; v < n; ++v) fr.positions[v] = x.segment<3>(3 * v);
    fr.body = body.mesh().vertices;
    fr.stress_kpa.resize(ne);
    for (int e = 0; e < ne; ++e) {
      const MembraneElement& el = model.elements[e];
      const MembraneStress s = membrane_stress(fr.positions[el.v[0]], fr.positions[el.v[1]], fr.positions[el.v[2]],
                                               el, model.materials[el.material]);
      fr.stress_kpa[e] = std::max(0.0, s.principal_max_kpa);
      result.max_stress_kpa[e] = std::max(result.max_stress_kpa[e], fr.stress_kpa[e]);
    }
    update_body_sliding(sliding, body, x, o.sliding_distance_mm);
    fr.sliding_mm = sliding.sliding_mm;
    fr.touching = static_cast<int>(std::count(sliding.touching.begin(), sliding.touching.end(), 1));
    fr.elastic_energy_uj = elastic_energy(model, x);
    fr.kinetic_energy_uj = 0.0;
    fr.gravity_energy_uj = 0.0;
    for (int v = 0; v < n; ++v) {
      const double m = model.vertex_mass_kg[v];
      fr.kinetic_energy_uj += 0.5 * m * state.velocities_mm_s.segment<3>(3 * v).squaredNorm();
      fr.gravity_energy_uj -= m * o.gravity_mm_s2.dot(x.segment<3>(3 * v));
    }
    result.measure_seconds += t.seconds();
  };

  ClothFrame first;
  first.min_distance_mm = min_distance_to_body(body, state.positions_mm, o.distance_range_mm, pinned);
  measure(first);
  result.min_distance_mm = first.min_distance_mm;
  if (on_frame) on_frame(first);
  result.frames.push_back(std::move(first));

  const std::vector<Vec3> start_pose = body.mesh().vertices;
  std::vector<Vec3> pins(model.pinned.size());
  for (int f = 1; f <= o.frames; ++f) {
    ClothFrame fr;
    fr.frame = f;
    fr.min_distance_mm = std::numeric_limits<double>::infinity();
    const std::vector<Vec3>& from = body_frames.empty() ? start_pose : body_frames[f - 1];
    const std::vector<Vec3>& to = body_frames.empty() ? start_pose : body_frames[f];
    for (int s = 1; s <= o.substeps; ++s) {
      const double a = static_cast<double>(s) / o.substeps;
      std::vector<Vec3> pose(to.size());
      for (size_t k = 0; k < to.size(); ++k) pose[k] = (1 - a) * from[k] + a * to[k];
      for (size_t k = 0; k < model.pinned.size(); ++k) {
        const int v = model.pinned[k];
        if (is_attached[k]) {
          pins[k] = face_point(body_mesh, pose, att[k].face, att[k].bary) +
                    face_frame(body_mesh, pose, att[k].face) * att[k].local;
        } else {
          pins[k] = model.rest_positions[v];
        }
      }
      const std::vector<Vec3> body_end = body_frames.empty() ? std::vector<Vec3>{} : pose;
      StepResult r;
      try {
        if (preview) {
          PreviewStepResult p = preview_step(*pws, state, body, body_end, pins, so.time_step_s, o.gravity_mm_s2,
                                             o.contact.distance_mm, o.contact.friction, o.preview);
          r.state = std::move(p.state);
          r.converged = p.converged;
          r.factorizations = p.substeps;  // one a (split) step
          r.substeps = p.substeps;
          r.contacts = p.contacts;
          r.min_distance_mm = p.min_distance_mm;
          r.seconds.factor = p.factor_seconds;
          r.seconds.evaluate = p.iterate_seconds;
          r.seconds.max_step = p.contact_seconds;
          fr.preview_iterations += p.iterations;
          fr.preview_last_move_mm = std::max(fr.preview_last_move_mm, p.last_move_mm);
        } else {
          r = step_simulation(*ws, state, body, body_end, pins, so);
        }
      } catch (const SolverError& e) {
        throw SolverError(fmt::format("cloth: frame {} (step {} of {}): {}", f, s, o.substeps, e.what()));
      }
      state = std::move(r.state);
      if (!body_frames.empty()) body.move_to(pose);
      fr.newton_iterations += r.newton_iterations;
      fr.quasi_newton_iterations += r.quasi_newton_iterations;
      fr.factorizations += r.factorizations;
      fr.converged = fr.converged && r.converged;
      fr.solves_at_iteration_limit += r.solves_at_iteration_limit;
      fr.steps += r.substeps;
      fr.contacts = r.contacts;
      fr.max_force_mn = r.max_force_mn;
      fr.min_distance_mm = std::min(fr.min_distance_mm, r.min_distance_mm);
      add(fr.seconds, r.seconds);
    }
    // The step reports distances within the contact distance only; farther, measure.
    if (!std::isfinite(fr.min_distance_mm))
      fr.min_distance_mm = min_distance_to_body(body, state.positions_mm, o.distance_range_mm, pinned);
    measure(fr);
    result.converged = result.converged && fr.converged;
    result.newton_iterations += fr.newton_iterations;
    result.quasi_newton_iterations += fr.quasi_newton_iterations;
    result.factorizations += fr.factorizations;
    result.preview_iterations += fr.preview_iterations;
    result.steps += fr.steps;
    result.min_distance_mm = std::min(result.min_distance_mm, fr.min_distance_mm);
    add(result.seconds, fr.seconds);
    if (on_frame) on_frame(fr);
    result.frames.push_back(std::move(fr));
  }
  result.max_sliding_mm = sliding.max_sliding_mm;
  return result;
}

}  // namespace knitforge
