#include "knitforge/design/tube/tube_spacing.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

TubeSpacing tube_spacing(const TriMesh& mesh, const TubeField& field, int levels, int fractions,
                         const std::optional<Vec3>& start) {
  if (levels < 2 || fractions < 4) throw InvalidInput("tube spacing: needs at least 2 levels and 4 fractions");
  TubeSpacing s;
  s.levels = levels;
  s.fractions = fractions;
  std::vector<double> u(static_cast<size_t>(levels) + 1);
  for (int j = 0; j <= levels; ++j) u[static_cast<size_t>(j)] = static_cast<double>(j) / levels;
  s.curves = tube_round_curves(mesh, field, u, start);
  s.along.assign(static_cast<size_t>(fractions), std::vector<double>(static_cast<size_t>(levels) + 1, 0.0));
  std::vector<Vec3> prev(static_cast<size_t>(fractions));
  for (int j = 0; j <= levels; ++j) {
    for (int i = 0; i < fractions; ++i) {
      const Vec3 p = round_point_at(s.curves[static_cast<size_t>(j)], static_cast<double>(i) / fractions);
      if (j > 0) {
        s.along[static_cast<size_t>(i)][static_cast<size_t>(j)] =
            s.along[static_cast<size_t>(i)][static_cast<size_t>(j - 1)] + (p - prev[static_cast<size_t>(i)]).norm();
      }
      prev[static_cast<size_t>(i)] = p;
    }
  }
  s.inside.assign(static_cast<size_t>(levels) + 1, std::numeric_limits<double>::max());
  for (int j = 0; j <= levels; ++j)
    for (int i = 0; i < fractions; ++i)
      s.inside[static_cast<size_t>(j)] = std::min(s.inside[static_cast<size_t>(j)], s.along[static_cast<size_t>(i)][static_cast<size_t>(j)]);
  for (int i = 1; i < fractions; ++i) {
    const double total = s.along[static_cast<size_t>(i)].back();
    if (total < s.along[static_cast<size_t>(s.inside_fraction)].back()) s.inside_fraction = i;
    if (total > s.along[static_cast<size_t>(s.outside_fraction)].back()) s.outside_fraction = i;
  }
  const double lo = s.along[static_cast<size_t>(s.inside_fraction)].back();
  s.ratio = lo > 0.0 ? s.along[static_cast<size_t>(s.outside_fraction)].back() / lo : 1.0;
  return s;
}

double TubeSpacing::along_at(double f, double u) const {
  f -= std::floor(f);
  const double x = f * fractions, y = std::clamp(u, 0.0, 1.0) * levels;
  const int i0 = std::min(static_cast<int>(x), fractions - 1), j0 = std::min(static_cast<int>(y), levels - 1);
  const int i1 = (i0 + 1) % fractions;
  const double a = x - i0, b = y - j0;
  auto at = [&](int i, int j) { return along[static_cast<size_t>(i)][static_cast<size_t>(j)]; };
  return (1 - a) * ((1 - b) * at(i0, j0) + b * at(i0, j0 + 1)) + a * ((1 - b) * at(i1, j0) + b * at(i1, j0 + 1));
}

double TubeSpacing::inside_at(double u) const {
  const double y = std::clamp(u, 0.0, 1.0) * levels;
  const int j0 = std::min(static_cast<int>(y), levels - 1);
  const double b = y - j0;
  return (1 - b) * inside[static_cast<size_t>(j0)] + b * inside[static_cast<size_t>(j0) + 1];
}

double TubeSpacing::level_of_inside(double d) const {
  int j = 0;
  while (j + 1 < levels && inside[static_cast<size_t>(j) + 1] < d) ++j;
  const double d0 = inside[static_cast<size_t>(j)], d1 = inside[static_cast<size_t>(j) + 1];
  const double t = d1 > d0 ? std::clamp((d - d0) / (d1 - d0), 0.0, 1.0) : 0.5;
  return (j + t) / levels;
}

double TubeSpacing::level_at(double f, double d) const {
  double lo = 0.0, hi = 1.0;
  if (d <= 0.0) return 0.0;
  if (d >= along_at(f, 1.0)) return 1.0;
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    (along_at(f, mid) < d ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Vec3 TubeSpacing::point(double f, double u) const {
  const double y = std::clamp(u, 0.0, 1.0) * levels;
  const int j0 = std::min(static_cast<int>(y), levels - 1);
  const double b = y - j0;
  return (1 - b) * round_point_at(curves[static_cast<size_t>(j0)], f) +
         b * round_point_at(curves[static_cast<size_t>(j0) + 1], f);
}

std::vector<Vec3> TubeSpacing::line(int i) const {
  std::vector<Vec3> out;
  for (const RoundCurve& c : curves) out.push_back(round_point_at(c, static_cast<double>(i) / fractions));
  return out;
}

CourseSpacing measure_course_spacing(const StitchMesh& mesh, const TubeSpacing& spacing, double stitch_width,
                                     double stitch_height) {
  CourseSpacing out;
  const std::vector<Vec3> lines[2] = {spacing.line(spacing.inside_fraction), spacing.line(spacing.outside_fraction)};
  SideSpacing* sides[2] = {&out.inside, &out.outside};
  for (const Stitch& s : mesh.stitches) {
    if (s.type != StitchType::Knit) continue;
    const Vec3& bl = mesh.vertices[static_cast<size_t>(s.v[0])];
    const Vec3& br = mesh.vertices[static_cast<size_t>(s.v[1])];
    const Vec3& tr = mesh.vertices[static_cast<size_t>(s.v[2])];
    const Vec3& tl = mesh.vertices[static_cast<size_t>(s.v[3])];
    const Vec3 centre = 0.25 * (bl + br + tr + tl);
    // Course spacing: from the bottom side's middle to the top side's, less
    // its part along the course (wales that lean do not make a stitch taller).
    const Vec3 up = 0.5 * (tl + tr) - 0.5 * (bl + br);
    const Vec3 along = ((br - bl) + (tr - tl)).normalized();
    const double h = (up - up.dot(along) * along).norm() / stitch_height;
    out.all.min = out.all.stitches == 0 ? h : std::min(out.all.min, h);
    out.all.max = out.all.stitches == 0 ? h : std::max(out.all.max, h);
    ++out.all.stitches;
    out.all.taller += h > 1.25 ? 1 : 0;
    for (int side = 0; side < 2; ++side) {
      const std::vector<Vec3>& l = lines[side];
      double best = std::numeric_limits<double>::max();
      for (size_t k = 0; k + 1 < l.size(); ++k) best = std::min(best, (closest_point_on_segment(centre, l[k], l[k + 1]) - centre).norm());
      if (best > stitch_width) continue;
      SideSpacing& ss = *sides[side];
      ss.min = ss.stitches == 0 ? h : std::min(ss.min, h);
      ss.max = ss.stitches == 0 ? h : std::max(ss.max, h);
      ++ss.stitches;
      ss.taller += h > 1.25 ? 1 : 0;
    }
  }
  return out;
}

}  // namespace knitforge
