#include "knitforge/design/shortrow/tessellate_wales.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/design/shortrow/tessellate_strip.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

/// True when the wales run the same way at the two samples (the wale
/// directions agree). Samples of neighbouring wales that run against each
/// other lie on the two sides of a cut (or of a narrow notch) and must not
/// be paired: a strip between them would cross it.
bool same_way(const std::vector<Vec3>& w, size_t k, const std::vector<Vec3>& v, size_t m) {
  return wale_tangent(w, k).dot(wale_tangent(v, m)) > 0.0;
}

/// For every even sample of `from`, the piece of `to` holding the nearest
/// even sample whose wale runs the same way (0 when `to` has one piece; -1
/// when `to` is empty or no sample runs the same way).
std::vector<int> nearest_piece(const WaleCurve& from, const std::vector<WaleCurve>& to) {
  std::vector<int> owner;
  for (size_t k = 0; k < from.points.size(); k += 2) {
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    if (to.size() == 1) {
      best = 0;
    } else {
      for (size_t q = 0; q < to.size(); ++q) {
        for (size_t m = 0; m < to[q].points.size(); m += 2) {
          if (!same_way(from.points, k, to[q].points, m)) continue;
          const double d = (from.points[k] - to[q].points[m]).squaredNorm();
          if (d < best_d) {
            best_d = d;
            best = static_cast<int>(q);
          }
        }
      }
    }
    owner.push_back(best);
  }
  return owner;
}

/// The longest run of consecutive even samples owned by `piece`, as sample
/// indices [first, last] into the points; {-1, -1} when it has fewer than
/// two even samples (one segment pair). Runs of different pieces never
/// overlap, so no wale segment is used by two strips on the same side.
std::pair<int, int> owned_range(const std::vector<int>& owner, int piece) {
  int best_first = -1, best_len = 0;
  for (size_t k = 0; k < owner.size();) {
    if (owner[k] != piece) {
      ++k;
      continue;
    }
    size_t e = k;
    while (e < owner.size() && owner[e] == piece) ++e;
    if (static_cast<int>(e - k) > best_len) {
      best_len = static_cast<int>(e - k);
      best_first = static_cast<int>(k);
    }
    k = e;
  }
  if (best_len < 2) return {-1, -1};
  return {2 * best_first, 2 * (best_first + best_len - 1)};
}

/// Even sample of `w` in [lo, hi] nearest to sample k of `v`, among those
/// where the two wales run the same way (all of them when none does). Ties
/// (distances within tie_mm: samples at one position, as the ends of a wale
/// that runs around on both lips of a seam, which the field places up to
/// its tolerance apart) go to the sample at the nearest relative position
/// along the wale, then to the lower index.
int nearest_even(const std::vector<Vec3>& w, int lo, int hi, const std::vector<Vec3>& v, int k, double tie_mm) {
  int best = -1, any = lo;
  double best_d = std::numeric_limits<double>::infinity(), any_d = best_d;
  const double at = static_cast<double>(k) / std::max<size_t>(v.size() - 1, 1);
  auto offset = [&](int m) { return std::abs(static_cast<double>(m) / std::max<size_t>(w.size() - 1, 1) - at); };
  auto tie = [&](double d, double e) { return std::isfinite(e) && std::abs(std::sqrt(d) - std::sqrt(e)) <= tie_mm; };
  for (int m = lo; m <= hi; m += 2) {
    const double d = (w[m] - v[k]).squaredNorm();
    if (tie(d, any_d) ? offset(m) < offset(any) : d < any_d) {
      any_d = std::min(d, any_d);
      any = m;
    }
    if ((tie(d, best_d) ? offset(m) < offset(best) : d < best_d) && same_way(w, m, v, k)) {
      best_d = std::min(d, best_d);
      best = m;
    }
  }
  return best >= 0 ? best : any;
}

/// Shortens the overhang of the longer wale beyond each end of the shorter
/// one to half its length (see the header). An overhang of n segments (n
/// even) should lose n / 2, but only whole pairs can go: when n / 2 is odd,
/// one segment more or one fewer than half is kept, whichever keeps `carry`
/// (segments kept beyond half, summed over the ends trimmed so far) closer
/// to zero. Rounding every such end the same way would add (or remove) about
/// half a stitch per boundary crossing.
void trim_overhangs(const std::vector<Vec3>& a, const std::vector<Vec3>& b, int& a0, int& a1, int& b0,
                    int& b1, int& carry, double tie_mm) {
  auto trim = [&carry](int n) {  // segments to remove from an overhang of n (even)
    const int lo = 2 * ((n / 2) / 2);
    if ((n / 2) % 2 == 0) return lo;
    if (std::abs(carry + 1) <= std::abs(carry - 1)) {
      carry += 1;  // keeps one segment more than half
      return lo;
    }
    carry -= 1;  // keeps one segment fewer than half
    return lo + 2;
  };
  if (a1 - a0 < 2 || b1 - b0 < 2) return;
  // Bottom ends.
  const int jb = nearest_even(b, b0, b1, a, a0, tie_mm);
  const int ia = nearest_even(a, a0, a1, b, b0, tie_mm);
  if (jb > b0) {
    b0 += std::min(trim(jb - b0), b1 - b0 - 2);
  } else if (ia > a0) {
    a0 += std::min(trim(ia - a0), a1 - a0 - 2);
  }
  // Top ends.
  const int jt = nearest_even(b, b0, b1, a, a1, tie_mm);
  const int it = nearest_even(a, a0, a1, b, b1, tie_mm);
  if (jt < b1) {
    b1 -= std::min(trim(b1 - jt), b1 - b0 - 2);
  } else if (it < a1) {
    a1 -= std::min(trim(a1 - it), a1 - a0 - 2);
  }
}

/// Which ends of a strip carry the apex of a fan of short-row ends.
struct FanEnds {
  bool a_low = false, a_high = false, b_low = false, b_high = false;
};

FanEnds fan_ends(const StripTessellation& t, int nb) {
  FanEnds f;
  for (const StripStep& st : t.steps) {
    if (st.op == StripOperator::BFan) (st.i == 0 ? f.a_low : f.a_high) = true;
    if (st.op == StripOperator::AAdvance && st.j == 0) f.b_low = true;
    if (st.op == StripOperator::AAdvance && st.j == nb) f.b_high = true;
  }
  return f;
}

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -Vec3::Constant(std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool contains(const Vec3& p, double margin) const {
    return (p.array() >= lo.array() - margin).all() && (p.array() <= hi.array() + margin).all();
  }
};

}  // namespace

WaleTessellation tessellate_wales(const WaleCurves& wales, const KnitParams& params,
                                  const TessellateWalesOptions& options) {
  const double sw = params.stitch_width, sh = params.stitch_height;
  const double diffusion_length = options.diffusion_length.value_or(sw);
  if (!(diffusion_length > 0.0)) {
    throw InvalidInput(
        fmt::format("tessellate wales: diffusion length {} mm must be positive", diffusion_length));
  }
  int nonempty = 0;
  for (const auto& l : wales.wales) nonempty += l.empty() ? 0 : 1;
  if (nonempty < 2) {
    throw InvalidInput(
        fmt::format("tessellate wales: only {} level(s) of the field carry a wale; at least two are needed "
                    "for one strip of "
                    "stitches: use a smaller stitch width (now {} mm)",
                    nonempty, sw));
  }

  WaleTessellation out;
  // Vertices: all samples, wale by wale.
  std::vector<std::vector<int>> offset(wales.wales.size());
  int flat = 0;
  for (size_t l = 0; l < wales.wales.size(); ++l) {
    for (const WaleCurve& w : wales.wales[l]) {
      offset[l].push_back(out.mesh.num_vertices());
      for (size_t k = 0; k < w.points.size(); ++k) {
        out.mesh.vertices.push_back(w.points[k]);
        out.vertex_wale.push_back(flat);
        out.vertex_sample.push_back(static_cast<int>(k));
      }
      ++flat;
    }
  }

  const double margin = 4.0 * diffusion_length;
  std::vector<char> paired_flat(flat, 0);
  int trim_carry = 0;  // see trim_overhangs()
  int flat_base = 0;
  for (size_t l = 0; l + 1 < wales.wales.size(); ++l) {
    const auto& lower = wales.wales[l];
    const auto& upper = wales.wales[l + 1];
    const int upper_base = flat_base + static_cast<int>(lower.size());
    std::vector<std::vector<int>> lower_owner(lower.size()), upper_owner(upper.size());
    for (size_t p = 0; p < lower.size(); ++p) lower_owner[p] = nearest_piece(lower[p], upper);
    for (size_t q = 0; q < upper.size(); ++q) upper_owner[q] = nearest_piece(upper[q], lower);
    for (size_t p = 0; p < lower.size(); ++p) {
      for (size_t q = 0; q < upper.size(); ++q) {
        auto [a0, a1] = owned_range(lower_owner[p], static_cast<int>(q));
        auto [b0, b1] = owned_range(upper_owner[q], static_cast<int>(p));
        if (a0 < 0 || b0 < 0) continue;
        const int a0_owned = a0, a1_owned = a1, b0_owned = b0, b1_owned = b1;
        trim_overhangs(lower[p].points, upper[q].points, a0, a1, b0, b1, trim_carry, 0.01 * sh);
        StripOptions so;
        so.stitch_width = sw;
        so.stitch_height = sh;
        so.lambda = options.lambda;
        so.mu = options.mu;
        so.diffusion_length = diffusion_length;
        so.strip_index = out.num_strips;
        StripTessellation t;
        std::vector<Vec3> a, b;
        for (;;) {
          a.assign(lower[p].points.begin() + a0, lower[p].points.begin() + a1 + 1);
          b.assign(upper[q].points.begin() + b0, upper[q].points.begin() + b1 + 1);
          Box box;
          for (const Vec3& x : a) box.add(x);
          for (const Vec3& x : b) box.add(x);
          so.previous_apexes.clear();
          for (size_t k = 0; k < out.apexes.size(); ++k) {
            if (!out.apex_on_wale_end[k] && box.contains(out.apexes[k], margin)) {
              so.previous_apexes.push_back(out.apexes[k]);
            }
          }
          t = tessellate_strip(a, b, so);
          // A fan of short-row ends whose apex is an end of the strip but
          // not of the paired run (an end that trim_overhangs() moved)
          // would sit in the middle of that wale, next to the stitches
          // across it, and become a detached column of stitches in the
          // post-processing: give the trimmed samples back and retry.
          const FanEnds f = fan_ends(t, static_cast<int>(b.size()) / 2);
          bool grown = false;
          if (f.a_low && a0 > a0_owned) a0 -= 2, grown = true;
          if (f.a_high && a1 < a1_owned) a1 += 2, grown = true;
          if (f.b_low && b0 > b0_owned) b0 -= 2, grown = true;
          if (f.b_high && b1 < b1_owned) b1 += 2, grown = true;
          if (!grown) break;
        }
        const int base_a = offset[l][p] + a0, base_b = offset[l + 1][q] + b0;
        const int na = static_cast<int>(a.size());
        for (const StripFace& f : t.faces) {
          Stitch s;
          s.type = f.type;
          s.direction = static_cast<int8_t>(f.direction);
          s.wale = static_cast<int>(l);
          for (int k = 0; k < 4; ++k) {
            const int id = f.corners[k];
            s.v[k] = id < 0 ? -1 : (id < na ? base_a + id : base_b + id - na);
          }
          out.mesh.stitches.push_back(s);
          out.stitch_strip.push_back(out.num_strips);
          out.stitch_level.push_back(static_cast<int>(l));
        }
        for (const StripApex& ap : t.apexes) {
          out.apexes.push_back(ap.position);
          out.apex_on_wale_end.push_back(ap.on_wale_end ? 1 : 0);
        }
        out.lambda_growths += t.lambda_growths;
        out.max_lambda = std::max(out.max_lambda, t.lambda);
        out.cost += t.cost;
        paired_flat[flat_base + p] = 1;
        paired_flat[upper_base + q] = 1;
        ++out.num_strips;
      }
    }
    flat_base = upper_base;
  }
  for (char c : paired_flat) out.unpaired_pieces += c ? 0 : 1;
  if (out.mesh.stitches.empty()) {
    throw InvalidInput("tessellate wales: no strip between neighbouring wales could be formed");
  }
  return out;
}

}  // namespace knitforge
