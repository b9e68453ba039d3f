#include "knitforge/design/flatten/flatten_surface.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "knitforge/geometry/slim_flatten.h"
#include "knitforge/geometry/surface_checks.h"
#include "knitforge/geometry/tutte_embedding.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {
std::vector<Vec2> align_pattern_to_reference(const TriMesh& mesh, const std::vector<Vec2>& uv) {
  if (static_cast<int>(uv.size()) != mesh.num_vertices()) {
    throw InvalidInput("align_pattern_to_reference: one 2D position per vertex needed");
  }
  Vec3 normal = Vec3::Zero();
  for (const auto& t : mesh.faces) {
    normal += (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
  }
  if (!(normal.norm() > 0.0)) throw InvalidInput("align_pattern_to_reference: the mesh has zero area");
  normal.normalize();
  Vec3 ex = Vec3::UnitX() - normal.x() * normal;
  if (ex.norm() < 0.1) ex = Vec3::UnitY() - normal.y() * normal;
  ex.normalize();
  const Vec3 ey = normal.cross(ex);
  std::vector<char> used(uv.size(), 0);
  for (const auto& t : mesh.faces) {
    for (int v : t) used[v] = 1;
  }
  Vec2 cu = Vec2::Zero();
  Vec2 cr = Vec2::Zero();
  int count = 0;
  for (size_t v = 0; v < uv.size(); ++v) {
    if (!used[v]) continue;
    cu += uv[v];
    cr += Vec2(mesh.vertices[v].dot(ex), mesh.vertices[v].dot(ey));
    ++count;
  }
  cu /= count;
  cr /= count;
  Mat2 S = Mat2::Zero();
  for (size_t v = 0; v < uv.size(); ++v) {
    if (!used[v]) continue;
    const Vec2 r(mesh.vertices[v].dot(ex), mesh.vertices[v].dot(ey));
    S += (r - cr) * (uv[v] - cu).transpose();
  }
  const double angle = std::atan2(S(1, 0) - S(0, 1), S(0, 0) + S(1, 1));
  Mat2 R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  std::vector<Vec2> out(uv.size());
  for (size_t v = 0; v < uv.size(); ++v) out[v] = used[v] ? Vec2(R * (uv[v] - cu) + cr) : uv[v];
  return out;
}

namespace {

double angle_deg(const Vec2& a, const Vec2& b) {
  const double c = a.x() * b.x() + a.y() * b.y();
  const double s = a.x() * b.y() - a.y() * b.x();
  return std::abs(std::atan2(s, c)) * 180.0 / std::numbers::pi;
}

}  // namespace

Flattening flatten_surface(const TriMesh& mesh, const std::vector<DartSpec>& darts,
                           const FlattenOptions& options) {
  require_disk(mesh, "the surface to flatten");
  Timer timer;
  CutDarts cut = cut_darts(mesh, darts);
  const double seconds_cut = timer.seconds();
  Flattening out = flatten_cut(std::move(cut), options);
  out.seconds_cut = seconds_cut;
  return out;
}

namespace {

// A start without flipped faces for slim_flatten(): the unconstrained ARAP
// result when it has none, else Tutte's embedding of the surface with the
// darts closed (bijective for a disk; the two copies of a cut vertex start
// at one point), else Tutte's embedding of the cut mesh.
std::vector<Vec2> injective_start(const CutDarts& cut, const std::vector<Vec2>& unconstrained,
                                  const std::vector<Vec2>& tutte) {
  if (!has_flipped_face(cut.mesh, unconstrained)) return unconstrained;
  if (!cut.vertex_class.empty()) {
    try {
      const std::vector<Vec2> closed = tutte_embedding(closed_darts_mesh(cut)).uv;
      std::vector<Vec2> uv(cut.mesh.vertices.size());
      for (size_t v = 0; v < uv.size(); ++v) uv[v] = closed[static_cast<size_t>(cut.vertex_class[v])];
      if (!has_flipped_face(cut.mesh, uv)) return align_pattern_to_reference(cut.mesh, uv);
    } catch (const TopologyError&) {
      // darts that touch each other: the closed surface is not a manifold disk
    }
  }
  if (!has_flipped_face(cut.mesh, tutte)) return align_pattern_to_reference(cut.mesh, tutte);
  throw SolverError(
      "flattening: no start without folded triangles was found (the surface may have degenerate, "
      "zero-area faces; remove them)");
}

}  // namespace

Flattening flatten_cut(CutDarts cut, const FlattenOptions& options) {
  Flattening out;
  Timer timer;
  out.mesh = cut.mesh;
  out.darts = cut.darts;

  ArapFlattenOptions arap;
  arap.max_iterations = options.max_iterations;
  if (options.progress) {
    arap.on_iteration = [&](int it) {
      if (it % 20 == 0) options.progress(fmt::format("ARAP, iteration {} of at most {}", it, arap.max_iterations));
    };
  }
  arap.tolerance = options.tolerance;
  arap.initial = tutte_embedding(out.mesh).uv;
  const std::vector<Vec2> tutte = arap.initial;
  // Without darts a folded ARAP pattern is replaced by the fold-free
  // solver's (below), so ARAP need not run to convergence once it stays folded.
  if (out.darts.empty()) arap.stop_after_folded_iterations = options.abandon_folded_arap_after;
  ArapFlattenResult first = arap_flatten(out.mesh, arap);
  out.iterations = first.iterations;
  std::vector<Vec2> uv = align_pattern_to_reference(out.mesh, first.uv);
  const std::vector<Vec2> unconstrained = uv;
  ArapFlattenResult result = std::move(first);
  if (!out.darts.empty()) {
    arap.initial = uv;
    for (const auto& d : out.darts) {
      (d.orientation == DartOrientation::Horizontal ? arap.equal_x : arap.equal_y)
          .emplace_back(d.notch_a, d.notch_b);
    }
    result = arap_flatten(out.mesh, arap);
    out.iterations += result.iterations;
    uv = std::move(result.uv);
  }
  out.converged = result.converged;
  out.relative_energy = result.relative_energy;
  out.arap_flipped_faces = static_cast<int>(result.flipped_faces.size());
  out.flipped_faces = result.flipped_faces;
  out.uv = std::move(uv);
  out.distortion = flattening_distortion(out.mesh, out.uv);
  out.stats = distortion_stats(out.mesh, out.uv, out.distortion);
  out.arap_max_abs_log_sigma = out.stats.max_abs_log_sigma();
  const bool folded = !out.flipped_faces.empty();
  if (folded || out.arap_max_abs_log_sigma > options.max_arap_log_sigma) {
    // ARAP folded the pattern (or nearly: a triangle squashed or stretched
    // beyond the limit): minimise the symmetric Dirichlet energy from a
    // fold-free start instead, which cannot fold (slim_flatten.h).
    SlimFlattenOptions slim;
    slim.initial = injective_start(cut, unconstrained, tutte);
    slim.max_iterations = options.max_iterations;
    slim.equal_x = arap.equal_x;
    slim.equal_y = arap.equal_y;
    if (options.progress) {
      options.progress("ARAP folded the pattern: the fold-free solver starts");
      slim.on_iteration = [&](int it) {
        if (it % 5 == 0) {
          options.progress(fmt::format("fold-free solver, iteration {} of at most {}", it, slim.max_iterations));
        }
      };
    }
    const SlimFlattenResult s = slim_flatten(out.mesh, slim);
    out.iterations += s.iterations;
    if (!s.constraints_met && folded) {
      size_t worst = 0;
      double worst_gap = -1.0;
      for (size_t i = 0; i < out.darts.size(); ++i) {
        const DartResult& d = out.darts[i];
        const Vec2 gap = s.uv[d.notch_a] - s.uv[d.notch_b];
        const double g = std::abs(d.orientation == DartOrientation::Horizontal ? gap.x() : gap.y());
        if (g > worst_gap) worst_gap = g, worst = i;
      }
      throw InvalidInput(fmt::format(
          "dart {} ({} {}) cannot be flattened without folding the pattern: its notches stay {:.3g} mm "
          "apart where they must align; move the dart, change its orientation or remove it",
          worst, to_string(out.darts[worst].type), to_string(out.darts[worst].orientation), worst_gap));
    }
    // (When the constraints are not met, the unfolded ARAP pattern stays.)
    std::vector<Vec2> suv = out.darts.empty() ? align_pattern_to_reference(out.mesh, s.uv) : s.uv;
    std::vector<FaceDistortion> sd = flattening_distortion(out.mesh, suv);
    const DistortionStats ss = distortion_stats(out.mesh, suv, sd);
    if (s.constraints_met && (folded || ss.max_abs_log_sigma() < out.stats.max_abs_log_sigma())) {
      out.uv = std::move(suv);
      out.distortion = std::move(sd);
      out.stats = ss;
      out.converged = s.converged;
      out.injective_solver = true;
      out.relative_energy = s.energy;
      out.flipped_faces = s.flipped_faces;
    }
  }
  out.stitch_max_abs_log_sigma = patch_max_abs_log_sigma(out.mesh, out.distortion, options.stitch_width);
  out.seconds_flatten = timer.seconds();

  for (size_t i = 0; i < out.darts.size(); ++i) {
    DartResult& d = out.darts[i];
    const Vec2 a = out.uv[d.notch_a];
    const Vec2 b = out.uv[d.notch_b];
    d.alignment_error =
        d.orientation == DartOrientation::Horizontal ? std::abs(a.x() - b.x()) : std::abs(a.y() - b.y());
    d.angle_deg = 0.0;
    for (int tip : d.tips) d.angle_deg = std::max(d.angle_deg, angle_deg(a - out.uv[tip], b - out.uv[tip]));
    d.angle_limit_deg = dart_angle_limit(d.orientation, options.stitch_width, options.stitch_height);
    d.angle_ok = d.angle_deg <= d.angle_limit_deg;
    if (!d.angle_ok && options.enforce_dart_angle) {
      throw InvalidInput(
          fmt::format("dart {} ({} {}): its legs open {:.1f} degrees in the pattern, more than the {:.1f} "
                      "degrees a {} dart can be knitted with at stitch size {} x {} mm; add more darts to "
                      "share the opening, or allow wide darts (they become boundaries sewn afterwards)",
                      i, to_string(d.type), to_string(d.orientation), d.angle_deg, d.angle_limit_deg,
                      to_string(d.orientation), options.stitch_width, options.stitch_height));
    }
  }
  return out;
}

}  // namespace knitforge
