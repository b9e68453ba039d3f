#include "knitforge/sim/body_sliding.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

BodySliding start_body_sliding(int n) {
  BodySliding s;
  s.anchor_face.assign(n, -1);
  s.anchor_bary.assign(n, Vec3::Zero());
  s.sliding_mm.assign(n, 0.0);
  s.max_sliding_mm.assign(n, 0.0);
  s.touching.assign(n, 0);
  return s;
}

void update_body_sliding(BodySliding& s, const KinematicBody& body, const Eigen::VectorXd& x, double near_mm) {
  const int n = static_cast<int>(s.anchor_face.size());
  if (x.size() != 3 * static_cast<Eigen::Index>(n)) {
    throw InvalidInput(fmt::format("sliding: {} coordinates for {} vertices", x.size(), n));
  }
  if (!(near_mm > 0 && std::isfinite(near_mm))) {
    throw InvalidInput(fmt::format("sliding: the touching distance {} mm must be positive", near_mm));
  }
  for (int v = 0; v < n; ++v) {
    const auto q = body.empty() ? std::nullopt : body.closest_point_within(x.segment<3>(3 * v), near_mm);
    s.touching[v] = q.has_value();
    if (!q) continue;
    if (s.anchor_face[v] < 0) {
      s.anchor_face[v] = q->face;
      s.anchor_bary[v] = q->where.bary;
      s.sliding_mm[v] = 0.0;
      continue;
    }
    s.sliding_mm[v] = (q->where.point - body.point(s.anchor_face[v], s.anchor_bary[v])).norm();
    s.max_sliding_mm[v] = std::max(s.max_sliding_mm[v], s.sliding_mm[v]);
  }
}

}  // namespace knitforge
