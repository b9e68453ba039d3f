#include "knitforge/geometry/resample_polyline.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

struct ArcPolyline {
  const std::vector<Vec3>& p;
  std::vector<double> cum;  // cumulative arc length per point

  double length() const { return cum.back(); }

  // The point at arc length s in [0, L] and its segment index.
  Vec3 at(double s, int* segment) const {
    const int n = static_cast<int>(p.size());
    if (s <= 0.0) {
      *segment = first_segment();
      return p.front();
    }
    if (s >= length()) {
      *segment = last_segment();
      return p.back();
    }
    // First i with cum[i+1] > s.
    const auto it = std::upper_bound(cum.begin(), cum.end(), s);
    int i = static_cast<int>(it - cum.begin()) - 1;
    i = std::clamp(i, 0, n - 2);
    const double len = cum[i + 1] - cum[i];
    *segment = i;
    if (len <= 0.0) return p[i];
    const double t = std::clamp((s - cum[i]) / len, 0.0, 1.0);
    return (1.0 - t) * p[i] + t * p[i + 1];
  }
  int first_segment() const {
    for (size_t i = 0; i + 1 < p.size(); ++i)
      if (cum[i + 1] > cum[i]) return static_cast<int>(i);
    return 0;
  }
  int last_segment() const {
    for (size_t i = p.size() - 1; i > 0; --i)
      if (cum[i] > cum[i - 1]) return static_cast<int>(i - 1);
    return 0;
  }
};

}  // namespace

ResampledPolyline resample_polyline(const std::vector<Vec3>& polyline, double target_length,
                                    const ResampleOptions& options) {
  if (!std::isfinite(target_length) || target_length <= 0.0) {
    throw InvalidInput(fmt::format("resample_polyline: the target segment length must be positive and "
                                   "finite, got {}",
                                   target_length));
  }
  if (polyline.size() < 2) {
    throw InvalidInput(fmt::format("resample_polyline: the polyline has {} point(s); at least 2 are "
                                   "needed",
                                   polyline.size()));
  }
  ArcPolyline arc{polyline, std::vector<double>(polyline.size(), 0.0)};
  for (size_t i = 0; i < polyline.size(); ++i) {
    if (!polyline[i].allFinite()) {
      throw InvalidInput(fmt::format("resample_polyline: point {} of the polyline is not finite", i));
    }
    if (i > 0) arc.cum[i] = arc.cum[i - 1] + (polyline[i] - polyline[i - 1]).norm();
  }
  const double L = arc.length();
  if (!(L >= 1e-9 * target_length)) {
    throw InvalidInput(fmt::format("resample_polyline: the polyline has (almost) zero length ({} mm, "
                                   "target {} mm); drop such a curve instead of resampling it",
                                   L, target_length));
  }
  const double ratio = L / target_length;
  if (ratio > 1e8) {
    throw InvalidInput(fmt::format("resample_polyline: {} segments would result; use a larger target "
                                   "length",
                                   ratio));
  }
  const int natural = std::max(1, static_cast<int>(std::lround(ratio)));

  ResampledPolyline out;
  out.input_length = L;
  if (natural % 2 == 0) {
    out.num_segments = natural;
    out.segment_length = L / natural;
  } else if (options.extend_ends) {
    out.num_segments = natural + 1;
    out.segment_length = target_length;
    out.extension = 0.5 * (out.num_segments * target_length - L);
  } else {
    int n = ratio >= natural ? natural + 1 : natural - 1;
    n = std::max(n, 2);
    out.num_segments = n;
    out.segment_length = L / n;
  }

  // End tangents (unit, pointing outwards) for the extension.
  Vec3 start_dir = Vec3::Zero(), end_dir = Vec3::Zero();
  if (out.extension > 0.0) {
    const double reach = std::min(target_length, L);
    int seg = 0;
    start_dir = polyline.front() - arc.at(reach, &seg);
    end_dir = polyline.back() - arc.at(L - reach, &seg);
    // A curve that returns to its end within one target length: fall back to
    // the end segments themselves.
    if (!(start_dir.norm() > 1e-9 * reach)) {
      const int i = arc.first_segment();
      start_dir = polyline[i] - polyline[i + 1];
    }
    if (!(end_dir.norm() > 1e-9 * reach)) {
      const int i = arc.last_segment();
      end_dir = polyline[i + 1] - polyline[i];
    }
    start_dir.normalize();
    end_dir.normalize();
  }

  const int n = out.num_segments;
  out.points.reserve(n + 1);
  out.arc_length.reserve(n + 1);
  out.segment.reserve(n + 1);
  for (int k = 0; k <= n; ++k) {
    double s = -out.extension + k * out.segment_length;
    if (k == n) s = L + out.extension;
    if (k == 0) s = -out.extension;
    Vec3 q;
    int seg = 0;
    if (s < 0.0) {
      q = polyline.front() + (-s) * start_dir;
      seg = -1;
    } else if (s > L) {
      q = polyline.back() + (s - L) * end_dir;
      seg = -2;
    } else {
      q = arc.at(s, &seg);
    }
    out.points.push_back(q);
    out.arc_length.push_back(s);
    out.segment.push_back(seg);
  }
  return out;
}

}  // namespace knitforge
