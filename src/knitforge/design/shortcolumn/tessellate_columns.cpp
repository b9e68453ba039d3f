#include "knitforge/design/shortcolumn/tessellate_columns.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/design/shortrow/tessellate_strip.h"
#include "knitforge/util/errors.h"

namespace knitforge {

ColumnTessellation tessellate_columns(const ColumnWales& wales, const KnitParams& params,
                                      const TessellateWalesOptions& options) {
  if (wales.strips.empty())
    throw InvalidInput(fmt::format(
        "short-column tessellation: no strip between two wales; the surface is narrower than two stitch widths "
        "(now {} mm) along the field: use a smaller stitch",
        params.stitch_width));
  const double sw = params.stitch_width;
  const double diffusion_length = options.diffusion_length.value_or(sw);
  ColumnTessellation out;
  out.mesh.vertices = wales.samples;
  const double margin = 4.0 * diffusion_length;
  for (size_t si = 0; si < wales.strips.size(); ++si) {
    const ColumnStrip& st = wales.strips[si];
    std::vector<Vec3> a, b;
    for (int id : st.a) a.push_back(wales.samples[static_cast<size_t>(id)]);
    for (int id : st.b) b.push_back(wales.samples[static_cast<size_t>(id)]);
    StripOptions so;
    so.stitch_width = sw;
    so.stitch_height = params.stitch_height;
    so.lambda = options.lambda;
    so.mu = options.mu;
    so.diffusion_length = diffusion_length;
    so.strip_index = static_cast<int>(si);
    so.start_increase = st.start_increase;
    so.end_decrease = st.end_decrease;
    so.allow_double_advance = false;  // four stacked short-row ends break a rule
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : a) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    for (const Vec3& p : b) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    for (const Vec3& p : out.apexes)
      if ((p.array() >= lo.array() - margin).all() && (p.array() <= hi.array() + margin).all()) so.previous_apexes.push_back(p);
    if (wales.parity[static_cast<size_t>(st.a[0])] != 0 || wales.parity[static_cast<size_t>(st.b[0])] != 0)
      throw InvalidInput(fmt::format("short-column tessellation: strip {} starts on an odd course; the wales' "
                                     "course parities are inconsistent (internal error)",
                                     si));
    const StripTessellation t = tessellate_strip(a, b, so);
    const int na = static_cast<int>(a.size());
    for (const StripFace& f : t.faces) {
      Stitch s;
      s.type = f.type;
      s.direction = static_cast<int8_t>(f.direction);
      s.wale = st.column;
      for (int k = 0; k < 4; ++k) {
        const int id = f.corners[static_cast<size_t>(k)];
        s.v[static_cast<size_t>(k)] = id < 0 ? -1 : (id < na ? st.a[static_cast<size_t>(id)] : st.b[static_cast<size_t>(id - na)]);
      }
      if (s.type == StitchType::Increase) ++out.increases;
      if (s.type == StitchType::Decrease) ++out.decreases;
      out.mesh.stitches.push_back(s);
      out.stitch_strip.push_back(static_cast<int>(si));
    }
    for (const StripApex& ap : t.apexes)
      if (!ap.on_wale_end) out.apexes.push_back(ap.position);
    out.lambda_growths += t.lambda_growths;
    out.max_lambda = std::max(out.max_lambda, t.lambda);
    out.cost += t.cost;
  }
  return out;
}

}  // namespace knitforge
