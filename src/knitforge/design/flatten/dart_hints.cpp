#include "knitforge/design/flatten/dart_hints.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/design/flatten/lift_map_to_surface.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

namespace {

/// Horizontal when `d` runs more along the pattern's x axis than along y.
DartOrientation orientation_along(const Vec2& d) {
  return std::abs(d.x()) >= std::abs(d.y()) ? DartOrientation::Horizontal : DartOrientation::Vertical;
}

double dist_to_darts(const Flattening& f, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& d : f.darts) {
    for (int v : d.path) best = std::min(best, (f.mesh.vertices[v] - p).norm());
  }
  return best;
}

// Is the 2D point inside the pattern, at least `margin` from its boundary?
bool inside_pattern(const Flattening& f, const std::vector<int>& boundary, const Vec2& p, double margin) {
  bool inside = false;
  for (const auto& t : f.mesh.faces) {
    const Vec2& a = f.uv[t[0]];
    const Vec2& b = f.uv[t[1]];
    const Vec2& c = f.uv[t[2]];
    auto cr = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double w0 = cr(b - p, c - p);
    const double w1 = cr(c - p, a - p);
    const double w2 = cr(a - p, b - p);
    if ((w0 >= 0 && w1 >= 0 && w2 >= 0) || (w0 <= 0 && w1 <= 0 && w2 <= 0)) {
      inside = true;
      break;
    }
  }
  if (!inside) return false;
  for (int v : boundary) {
    if ((f.uv[v] - p).norm() < margin) return false;
  }
  return true;
}

}  // namespace

std::optional<DartHint> propose_dart(const Flattening& f, const DartHintOptions& options) {
  for (double v : {options.depth, options.length, options.exclusion}) {
    if (!(v > 0.0 && v < 1.0))
      throw InvalidInput("propose_dart: depth, length and exclusion must be in (0, 1)");
  }
  const TriMesh& m = f.mesh;
  const int n = m.num_vertices();
  const Halfedges he = build_halfedges(n, m.faces);
  // Per-face log area scale, per-vertex area-weighted mean, smoothed over the 2-ring.
  std::vector<double> num(n, 0.0);
  std::vector<double> den(n, 0.0);
  double in_sum = 0.0, in_area = 0.0, bd_sum = 0.0, bd_area = 0.0;
  Vec3 lo = m.vertices.empty() ? Vec3::Zero() : m.vertices[0];
  Vec3 hi = lo;
  for (int fi = 0; fi < m.num_faces(); ++fi) {
    const auto& t = m.faces[fi];
    const double a =
        0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
    const double s = std::log(std::max(f.distortion[fi].sigma1, 1e-300)) +
                     std::log(std::max(f.distortion[fi].sigma2, 1e-300));
    bool on_boundary = false;
    for (int v : t) {
      num[v] += a * s;
      den[v] += a;
      on_boundary = on_boundary || he.is_boundary_vertex(v);
      lo = lo.cwiseMin(m.vertices[v]);
      hi = hi.cwiseMax(m.vertices[v]);
    }
    (on_boundary ? bd_sum : in_sum) += a * s;
    (on_boundary ? bd_area : in_area) += a;
  }
  std::vector<double> vs(n, 0.0);
  for (int v = 0; v < n; ++v) vs[v] = den[v] > 0.0 ? num[v] / den[v] : 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> next(n, 0.0);
    for (int v = 0; v < n; ++v) {
      if (he.is_isolated_vertex(v)) continue;
      const auto nb = he.vertex_neighbors(v);
      double acc = vs[v];
      for (int w : nb) acc += vs[w];
      next[v] = acc / (1.0 + nb.size());
    }
    vs = std::move(next);
  }
  const double size = (hi - lo).norm();
  const double exclusion = options.exclusion * size;
  const bool dome = in_area > 0.0 && bd_area > 0.0 && bd_sum / bd_area > in_sum / in_area;

  // The pattern's boundary vertices and size.
  std::vector<int> boundary;
  Vec2 plo(1e300, 1e300), phi(-1e300, -1e300);
  for (int v = 0; v < n; ++v) {
    if (he.is_isolated_vertex(v)) continue;
    if (he.is_boundary_vertex(v)) boundary.push_back(v);
    plo = plo.cwiseMin(f.uv[v]);
    phi = phi.cwiseMax(f.uv[v]);
  }
  const double pattern_size = (phi - plo).norm();
  DartHint hint;
  if (dome) {
    int b = -1;
    for (int v : boundary) {
      if (dist_to_darts(f, m.vertices[v]) < exclusion) continue;
      if (b < 0 || vs[v] > vs[b]) b = v;
    }
    // The centre of compression: the compressed vertices' pattern positions,
    // weighted by their compression and area.
    Vec2 centre = Vec2::Zero();
    double weight = 0.0;
    for (int v = 0; v < n; ++v) {
      if (he.is_isolated_vertex(v) || !(vs[v] < 0.0)) continue;
      centre += -vs[v] * den[v] * f.uv[v];
      weight += -vs[v] * den[v];
    }
    if (b < 0 || !(weight > 0.0) || !(vs[b] > 0.0)) return std::nullopt;
    centre /= weight;
    const Vec2 tip2 = f.uv[b] + options.depth * (centre - f.uv[b]);
    const Vec3 tip = pattern_points_to_surface(m, f.uv, {tip2})[0];
    if (dist_to_darts(f, tip) < 0.5 * exclusion) return std::nullopt;
    const Vec2 dir = centre - f.uv[b];
    hint.spec.type = DartType::OneEnd;
    hint.spec.orientation = orientation_along(dir);
    hint.spec.points = {DartWaypoint::at_position(m.vertices[b]), DartWaypoint::at_position(tip)};
    hint.score = vs[b];
    hint.reason = fmt::format(
        "dome-like: the boundary is stretched most at ({:.1f}, {:.1f}, {:.1f}) mm (area scale {:.3f}); "
        "one-end {} dart towards the centre of compression",
        m.vertices[b].x(), m.vertices[b].y(), m.vertices[b].z(), std::exp(vs[b]),
        to_string(hint.spec.orientation));
    return hint;
  }
  // Saddle: the most stretched inner vertex away from darts and boundary.
  const double margin = 0.05 * pattern_size;
  std::vector<int> order;
  for (int v = 0; v < n; ++v) {
    if (!he.is_isolated_vertex(v) && !he.is_boundary_vertex(v) && vs[v] > 0.0) order.push_back(v);
  }
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return vs[a] > vs[b] || (vs[a] == vs[b] && a < b); });
  const int max_tries = std::min<int>(static_cast<int>(order.size()), 50);
  for (int k = 0; k < max_tries; ++k) {
    const int s = order[k];
    if (dist_to_darts(f, m.vertices[s]) < exclusion) continue;
    // Mean stretch direction around s (sign-aligned dir1 of the incident faces).
    Vec2 dir = Vec2::Zero();
    for (int fi : he.vertex_faces(s)) {
      Vec2 d1 = f.distortion[fi].dir1;
      if (dir.dot(d1) < 0.0) d1 = -d1;
      dir += d1;
    }
    if (!(dir.norm() > 0.0)) continue;
    const Vec2 along = Vec2(-dir.y(), dir.x()).normalized();  // across the stretch
    for (double len = options.length * pattern_size; len > 0.05 * pattern_size; len *= 0.7) {
      const Vec2 a2 = f.uv[s] - 0.5 * len * along;
      const Vec2 b2 = f.uv[s] + 0.5 * len * along;
      if (!inside_pattern(f, boundary, a2, margin) || !inside_pattern(f, boundary, b2, margin)) continue;
      const auto p3 = pattern_points_to_surface(m, f.uv, {a2, b2});
      if (dist_to_darts(f, p3[0]) < 0.5 * exclusion || dist_to_darts(f, p3[1]) < 0.5 * exclusion) continue;
      hint.spec.type = DartType::TwoEnd;
      hint.spec.orientation = orientation_along(along);
      hint.spec.points = {DartWaypoint::at_position(p3[0]), DartWaypoint::at_position(m.vertices[s]),
                          DartWaypoint::at_position(p3[1])};
      hint.score = vs[s];
      hint.reason = fmt::format(
          "saddle-like: the inside is stretched most at ({:.1f}, {:.1f}, {:.1f}) mm (area scale {:.3f}); "
          "two-end {} dart across the stretch",
          m.vertices[s].x(), m.vertices[s].y(), m.vertices[s].z(), std::exp(vs[s]),
          to_string(hint.spec.orientation));
      return hint;
    }
  }
  return std::nullopt;
}

AutoDarts add_darts_automatically(const TriMesh& mesh, const std::vector<DartSpec>& darts, int max_darts,
                                  const FlattenOptions& options, const DartHintOptions& hint_options) {
  if (max_darts < 0) throw InvalidInput("add_darts_automatically: the number of darts must be >= 0");
  AutoDarts out;
  out.darts = darts;
  require_disk(mesh, "the surface to flatten");
  Timer timer;
  CutDarts current = cut_darts(mesh, out.darts);
  double seconds_cut = timer.seconds();
  out.flattening = flatten_cut(current, options);
  out.rms_sequence.push_back(out.flattening.stats.rms_log_sigma);
  out.max_sequence.push_back(out.flattening.stitch_max_abs_log_sigma);
  out.stop_reason = fmt::format("added the {} darts asked for", max_darts);
  // One dart alone may be too wide where several would share the opening:
  // the angle limit is checked once all darts are in.
  FlattenOptions loop_options = options;
  loop_options.enforce_dart_angle = false;
  for (int k = 0; k < max_darts; ++k) {
    const auto hint = propose_dart(out.flattening, hint_options);
    if (!hint) {
      out.stop_reason = "no further place for a dart (all candidates are near earlier darts)";
      break;
    }
    std::vector<DartSpec> trial = out.darts;
    trial.push_back(hint->spec);
    Flattening next;
    CutDarts trial_cut = current;
    try {
      timer.reset();
      append_dart(trial_cut, mesh, hint->spec);
      seconds_cut += timer.seconds();
      next = flatten_cut(trial_cut, loop_options);
    } catch (const InvalidInput& e) {
      out.stop_reason = fmt::format("the next dart was not added: {}", e.what());
      break;
    } catch (const TopologyError& e) {
      out.stop_reason = fmt::format("the next dart was not added: {}", e.what());
      break;
    }
    if (!(next.stats.rms_log_sigma < out.rms_sequence.back())) {
      out.stop_reason =
          fmt::format("the next dart did not lower the distortion (RMS log sigma {:.4f} -> {:.4f})",
                      out.rms_sequence.back(), next.stats.rms_log_sigma);
      break;
    }
    if (hint_options.require_lower_maximum && !(next.stitch_max_abs_log_sigma < out.max_sequence.back())) {
      out.stop_reason = fmt::format(
          "the next dart lowered the RMS distortion ({:.4f} -> {:.4f}) but not the largest (max |log sigma| "
          "at stitch scale {:.4f} -> {:.4f}, at its tip)",
          out.rms_sequence.back(), next.stats.rms_log_sigma, out.max_sequence.back(),
          next.stitch_max_abs_log_sigma);
      break;
    }
    if (!next.flipped_faces.empty()) {
      out.stop_reason = fmt::format("the next dart folds the pattern ({} flipped faces)", next.flipped_faces.size());
      break;
    }
    out.darts = std::move(trial);
    current = std::move(trial_cut);
    out.added.push_back(*hint);
    out.flattening = std::move(next);
    out.rms_sequence.push_back(out.flattening.stats.rms_log_sigma);
    out.max_sequence.push_back(out.flattening.stitch_max_abs_log_sigma);
  }
  out.flattening.seconds_cut = seconds_cut;
  if (options.enforce_dart_angle) {
    for (size_t i = 0; i < out.flattening.darts.size(); ++i) {
      const DartResult& d = out.flattening.darts[i];
      if (d.angle_ok) continue;
      throw InvalidInput(fmt::format(
          "dart {} ({} {}{}): its legs open {:.1f} degrees in the pattern, more than the {:.1f} degrees "
          "a {} dart can be knitted with; allow more automatic darts to share the opening, or allow "
          "wide darts (they become boundaries sewn afterwards)",
          i, to_string(d.type), to_string(d.orientation), i >= darts.size() ? ", added automatically" : "",
          d.angle_deg, d.angle_limit_deg, to_string(d.orientation)));
    }
  }
  return out;
}

}  // namespace knitforge
