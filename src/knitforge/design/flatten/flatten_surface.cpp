#include "knitforge/design/flatten/flatten_surface.h"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

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

Flattening flatten_cut(CutDarts cut, const FlattenOptions& options) {
  Flattening out;
  Timer timer;
  out.mesh = std::move(cut.mesh);
  out.darts = std::move(cut.darts);

  ArapFlattenOptions arap;
  arap.max_iterations = options.max_iterations;
  arap.tolerance = options.tolerance;
  arap.initial = tutte_embedding(out.mesh).uv;
  ArapFlattenResult first = arap_flatten(out.mesh, arap);
  out.iterations = first.iterations;
  std::vector<Vec2> uv = align_pattern_to_reference(out.mesh, first.uv);
  ArapFlattenResult result = std::move(first);
  if (!out.darts.empty()) {
    arap.initial = std::move(uv);
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
  out.flipped_faces = result.flipped_faces;
  out.uv = std::move(uv);
  out.distortion = flattening_distortion(out.mesh, out.uv);
  out.stats = distortion_stats(out.mesh, out.uv, out.distortion);
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
