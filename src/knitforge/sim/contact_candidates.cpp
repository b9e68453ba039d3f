#include "knitforge/sim/contact_candidates.h"

#include <algorithm>
#include <mutex>
#include <utility>

#include "knitforge/util/parallel_ranges.h"

namespace knitforge {

std::vector<ContactPair> find_contact_candidates(const KinematicBody& body, const Eigen::VectorXd& x, double dhat_mm,
                                                 const std::vector<char>& skip) {
  std::vector<ContactPair> pairs;
  if (body.empty()) return pairs;
  const Aabb reach = body.tree().bounds().inflated(dhat_mm);
  const int n = static_cast<int>(x.size() / 3);
  // The vertices' searches on all hardware threads, each range's pairs in
  // vertex order; the ranges joined in order.
  std::vector<std::pair<int, std::vector<ContactPair>>> found;
  std::mutex m;
  parallel_ranges(static_cast<size_t>(n), 2048, [&](size_t begin, size_t end) {
    std::vector<ContactPair> local;
    for (int v = static_cast<int>(begin); v < static_cast<int>(end); ++v) {
      if (!skip.empty() && skip[v]) continue;
      const Vec3 p = x.segment<3>(3 * v);
      if (reach.distance2(p) > 0) continue;
      for (const BodyPoint& q : body.closest_points_per_part_within(p, dhat_mm)) {
        if (q.distance2 < dhat_mm * dhat_mm) local.push_back({v, q});
      }
    }
    const std::lock_guard<std::mutex> lock(m);
    found.emplace_back(static_cast<int>(begin), std::move(local));
  });
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [begin, local] : found) pairs.insert(pairs.end(), local.begin(), local.end());
  return pairs;
}

}  // namespace knitforge
