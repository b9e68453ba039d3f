#include "knitforge/sim/contact_candidates.h"

namespace knitforge {

std::vector<ContactPair> find_contact_candidates(const KinematicBody& body, const Eigen::VectorXd& x, double dhat_mm,
                                                 const std::vector<char>& skip) {
  std::vector<ContactPair> pairs;
  if (body.empty()) return pairs;
  const Aabb reach = body.tree().bounds().inflated(dhat_mm);
  const int n = static_cast<int>(x.size() / 3);
  for (int v = 0; v < n; ++v) {
    if (!skip.empty() && skip[v]) continue;
    const Vec3 p = x.segment<3>(3 * v);
    if (reach.distance2(p) > 0) continue;
    for (const BodyPoint& q : body.closest_points_per_part_within(p, dhat_mm)) {
      if (q.distance2 < dhat_mm * dhat_mm) pairs.push_back({v, q});
    }
  }
  return pairs;
}

}  // namespace knitforge
