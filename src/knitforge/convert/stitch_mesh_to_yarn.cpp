#include "knitforge/convert/stitch_mesh_to_yarn.h"

#include <fmt/core.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>

#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

const Vec2 kKnitCorners[] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const Vec2 kLeftCorners[] = {{0, 0.5}, {1, 0}, {1, 1}};
const Vec2 kRightCorners[] = {{0, 0}, {1, 0.5}, {0, 1}};
const Vec2 kIncCorners[] = {{0.5, 0}, {1, 1}, {0, 1}};
const Vec2 kDecCorners[] = {{0, 0}, {1, 0}, {0.5, 1}};

/// The regular loop knitted left to right, in the unit square of the stitch
/// (u across, v up, z in yarn radii). The exit point (1, 0.04, -1) is not
/// part of the list: it is the next stitch's entry point.
struct LoopPoint {
  double u, v, z;
};
constexpr LoopPoint kLoop[] = {
    {0.00, 0.04, -1}, {0.18, 0.02, -1},  // sinker, behind the legs of the loop below
    {0.32, 0.10, -1},                    // foot, behind the head of the loop below
    {0.34, 0.36, +1}, {0.26, 0.68, +1}, {0.18, 1.00, +1},  // left leg, in front
    {0.20, 1.16, -1}, {0.50, 1.30, -1}, {0.80, 1.16, -1},  // head, behind the next course's legs
    {0.82, 1.00, +1}, {0.74, 0.68, +1}, {0.66, 0.36, +1},  // right leg, in front
    {0.68, 0.10, -1}, {0.82, 0.02, -1},                    // foot, sinker
};
constexpr int kLoopSize = sizeof(kLoop) / sizeof(kLoop[0]);
constexpr LoopPoint kExit{1.00, 0.04, -1};
constexpr int kHeadFirst = 6, kHeadLast = 8;  // indices of the head points
constexpr int kLegTopLeft = 5, kLegTopRight = 9;

/// A canonical point prepared for deformation: corner weights and z.
struct Weighted {
  std::array<double, 4> w;
  double z;
};

/// The corner weights of a point (x, y) of a stitch type's canonical frame:
/// bilinear for the quad, barycentric in the canonical triangle otherwise.
std::array<double, 4> canonical_weights(StitchType t, double x, double y) {
  if (t == StitchType::Knit) {
    return {(1 - x) * (1 - y), x * (1 - y), x * y, (1 - x) * y};
  }
  const auto c = canonical_corners(t);
  const Vec2 e1 = c[1] - c[0], e2 = c[2] - c[0], d = Vec2(x, y) - c[0];
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  const double b1 = (d.x() * e2.y() - d.y() * e2.x()) / det;
  const double b2 = (e1.x() * d.y() - e1.y() * d.x()) / det;
  return {1 - b1 - b2, b1, b2, 0.0};
}

/// Maps a unit-square point (u, v) of the loop design into the canonical
/// frame of type t: the identity for Knit, otherwise the quad whose collapsed
/// side is the apex (stitch.h), i.e. the degenerate bilinear map onto the
/// canonical triangle.
Vec2 square_to_canonical(StitchType t, double u, double v) {
  const auto c = canonical_corners(t);
  // Square corners BL, BR, TR, TL in the canonical frame.
  std::array<Vec2, 4> q;
  switch (t) {
    case StitchType::Knit: return {u, v};
    case StitchType::ShortRowLeft: q = {c[0], c[1], c[2], c[0]}; break;
    case StitchType::ShortRowRight: q = {c[0], c[1], c[1], c[2]}; break;
    case StitchType::Increase: q = {c[0], c[0], c[1], c[2]}; break;
    case StitchType::Decrease: q = {c[0], c[1], c[2], c[2]}; break;
    default: return {u, v};
  }
  return (1 - u) * (1 - v) * q[0] + u * (1 - v) * q[1] + u * v * q[2] + (1 - u) * v * q[3];
}

/// Variant key: type (3 bits), roles (4 bits), direction, open side.
struct Variant {
  StitchType type;
  uint8_t roles;
  bool right_to_left;
  bool open_left;  ///< for outside increase/decrease: the side without a course neighbour
  int key() const {
    return ((static_cast<int>(type) * 16 + (roles & 15)) * 2 + (right_to_left ? 1 : 0)) * 2 + (open_left ? 1 : 0);
  }
};
constexpr int kNumVariants = kNumStitchTypes * 16 * 2 * 2;

/// The canonical polyline of a variant in knitting order, exit point last.
std::vector<Weighted> build_variant(const Variant& var) {
  std::vector<LoopPoint> p(std::begin(kLoop), std::end(kLoop));
  p.push_back(kExit);
  // Knitting-frame changes (the loop as if knitted left to right).
  if (var.roles & kRoleBindOff) {
    // A closed loop just above the top side, leaning into the next stitch
    // of the bind-off chain.
    p[kHeadFirst] = {0.24, 1.04, -1};
    p[kHeadFirst + 1] = {0.62, 1.10, -1};
    p[kHeadLast] = {0.90, 1.02, 0};
  }
  if (var.type == StitchType::Decrease) {
    // The head closes into the top apex, where the two wales merge.
    p[kLegTopLeft].v = p[kLegTopRight].v = 0.86;
    p[kHeadFirst] = {0.35, 0.95, -1};
    p[kHeadFirst + 1] = {0.50, 0.98, -1};
    p[kHeadLast] = {0.65, 0.95, -1};
  }
  const bool flat_feet = (var.roles & kRoleCastOn) || var.type == StitchType::Increase;
  if (flat_feet) {
    for (int i : {1, 2, 12, 13}) p[i].z = 0;
  }
  // To the stitch frame: the loop of a right-to-left stitch is the mirror
  // image, so it enters on the right and leaves on the left.
  if (var.right_to_left) {
    for (LoopPoint& q : p) q.u = 1 - q.u;
  }
  // Stitch-frame changes that depend on the open side.
  const int n = static_cast<int>(p.size());
  if (var.roles & kRoleOutsideIncrease) {
    // The new loop on the open side is not hung on a loop below: flat foot.
    for (int i = 1; i + 1 < n; ++i) {
      const bool open_half = var.open_left ? p[i].u < 0.5 : p[i].u > 0.5;
      if (open_half && p[i].v < 0.2) p[i].z = 0;
    }
  }
  if (var.roles & kRoleOutsideDecrease) {
    // The edge loop is moved onto its inner neighbour's needle: head leans in.
    const double shift = var.open_left ? 0.25 : -0.25;
    for (int i = 1; i + 1 < n; ++i) {
      if (p[i].v > 1.02) p[i].u += shift;
      else if (p[i].v > 0.9) p[i].u += 0.5 * shift;
    }
  }
  std::vector<Weighted> out;
  out.reserve(p.size());
  for (const LoopPoint& lp : p) {
    const Vec2 c = square_to_canonical(var.type, lp.u, lp.v);
    out.push_back({canonical_weights(var.type, c.x(), c.y()), lp.z});
  }
  return out;
}

Vec3 facet_normal(const StitchMesh& mesh, const Stitch& s) {
  Vec3 n;
  if (s.corners() == 4) {
    n = (mesh.vertices[s.v[2]] - mesh.vertices[s.v[0]]).cross(mesh.vertices[s.v[3]] - mesh.vertices[s.v[1]]);
  } else {
    n = (mesh.vertices[s.v[1]] - mesh.vertices[s.v[0]]).cross(mesh.vertices[s.v[2]] - mesh.vertices[s.v[0]]);
  }
  const double len = n.norm();
  return len > 1e-300 ? Vec3(n / len) : Vec3::Zero();
}

}  // namespace

std::span<const Vec2> canonical_corners(StitchType t) {
  switch (t) {
    case StitchType::Knit: return kKnitCorners;
    case StitchType::ShortRowLeft: return kLeftCorners;
    case StitchType::ShortRowRight: return kRightCorners;
    case StitchType::Increase: return kIncCorners;
    case StitchType::Decrease: return kDecCorners;
  }
  return kKnitCorners;
}

Vec3 deform_canonical_point(const StitchMesh& mesh, int s, const CanonicalPoint& p, double yarn_radius) {
  const Stitch& st = mesh.stitches[s];
  const auto w = canonical_weights(st.type, p.x(), p.y());
  Vec3 r = p.z() * yarn_radius * facet_normal(mesh, st);
  for (int i = 0; i < st.corners(); ++i) r += w[i] * mesh.vertices[st.v[i]];
  return r;
}

YarnModel stitch_mesh_to_yarn(const StitchMesh& mesh, const KnitParams& params, const YarnOptions& opt) {
  if (!(params.stitch_width > 0 && std::isfinite(params.stitch_width)) ||
      !(params.stitch_height > 0 && std::isfinite(params.stitch_height))) {
    throw InvalidInput(fmt::format("stitch size {} x {} mm: both must be positive and finite", params.stitch_width,
                                   params.stitch_height));
  }
  if (!(opt.yarn_radius >= 0 && std::isfinite(opt.yarn_radius))) {
    throw InvalidInput(
        fmt::format("yarn radius {} mm: it must be positive and finite (or 0 for automatic)", opt.yarn_radius));
  }
  const double radius = opt.yarn_radius > 0 ? opt.yarn_radius : 0.12 * params.stitch_width;
  const int n = mesh.num_stitches();
  YarnModel model;
  if (n == 0) return model;

  const StitchAdjacency adj(mesh);
  // Global knitting order: one stroke from the stitch without a predecessor.
  int first = -1;
  for (int s = 0; s < n && first < 0; ++s) {
    if (adj.previous_stitch(s) < 0) first = s;
  }
  std::vector<int> order;
  order.reserve(n);
  if (first >= 0 && adj.previous_stitch(0) >= 0) {
    // The cast-on is a round: a tube with short rows when the walk from
    // `first` stops early.
    std::vector<char> seen(n, 0);
    int count = 0;
    for (int s = first; s >= 0 && !seen[s]; s = adj.next_stitch(s)) seen[s] = 1, ++count;
    if (count != n) first = -1;
  }
  if (first < 0) {
    // A tube (every course a round): no stitch starts the one-stroke order by
    // adjacency; its stitches are numbered in knitting order (as
    // map_to_stitch_mesh_topology() and the tube route number them), so
    // the yarn follows the index order when each stitch touches the next.
    auto touch = [&](int a, int b) {
      const Stitch &sa = mesh.stitches[a], &sb = mesh.stitches[b];
      for (int i = 0; i < sa.corners(); ++i)
        for (int j = 0; j < sb.corners(); ++j)
          if (sa.v[i] == sb.v[j]) return true;
      return false;
    };
    for (int s = 0; s < n; ++s) {
      if (s > 0 && !touch(s - 1, s)) {
        throw TopologyError(fmt::format(
            "the stitch mesh has no first stitch (every stitch has a previous one: a tube), and stitch {} does not "
            "touch stitch {}, so the stitches are not numbered in knitting order; run check_knittability",
            s, s - 1));
      }
      order.push_back(s);
    }
  } else {
    std::vector<char> seen(n, 0);
    for (int s = first; s >= 0; s = adj.next_stitch(s)) {
      if (seen[s]) {
        throw TopologyError(fmt::format("the knitting order returns to stitch {} after stitch {}; it must visit every "
                                        "stitch once (run check_knittability)",
                                        s, order.back()));
      }
      seen[s] = 1;
      order.push_back(s);
    }
  }
  if (static_cast<int>(order.size()) != n) {
    throw TopologyError(fmt::format("the knitting order stops at stitch {} after {} of {} stitches; the yarn cannot "
                                    "reach the others in one stroke (run check_knittability)",
                                    order.back(), order.size(), n));
  }

  std::map<int, size_t> yarn_index;
  std::vector<int> count_per;  // stitches per yarn, to reserve
  for (int s : order) {
    const int y = mesh.stitches[s].yarn;
    if (y < 0) throw InvalidInput(fmt::format("stitch {} has yarn index {}; yarn indices must be >= 0", s, y));
    yarn_index.emplace(y, 0);
  }
  for (auto& [y, i] : yarn_index) {
    i = model.yarns.size();
    model.yarns.push_back(Yarn{y, {}, {}});
  }
  count_per.assign(model.yarns.size(), 0);
  for (int s : order) ++count_per[yarn_index[mesh.stitches[s].yarn]];
  for (size_t i = 0; i < model.yarns.size(); ++i) {
    model.yarns[i].points.reserve(static_cast<size_t>(count_per[i]) * kLoopSize + 1);
    model.yarns[i].stitch.reserve(static_cast<size_t>(count_per[i]) * kLoopSize + 1);
  }

  std::vector<std::vector<Weighted>> cache(kNumVariants);
  std::vector<int> last_of_yarn(model.yarns.size(), -1);
  for (size_t oi = 0; oi < order.size(); ++oi) {
    const int s = order[oi];
    const Stitch& st = mesh.stitches[s];
    Variant var{st.type, static_cast<uint8_t>(st.roles & 15), st.direction < 0, false};
    if (st.roles & (kRoleOutsideIncrease | kRoleOutsideDecrease)) {
      var.open_left = adj.neighbor(s, Side::Left) < 0 || adj.neighbor(s, Side::Right) >= 0;
    }
    std::vector<Weighted>& pts = cache[var.key()];
    if (pts.empty()) pts = build_variant(var);
    const Vec3 nrm = radius * facet_normal(mesh, st);
    const int k = st.corners();
    std::array<Vec3, 4> corner;
    for (int i = 0; i < k; ++i) corner[i] = mesh.vertices[st.v[i]];
    const size_t yi = yarn_index[st.yarn];
    Yarn& yarn = model.yarns[yi];
    // All points but the exit, which is the next stitch's entry.
    for (size_t j = 0; j + 1 < pts.size(); ++j) {
      Vec3 p = pts[j].z * nrm;
      for (int i = 0; i < k; ++i) p += pts[j].w[i] * corner[i];
      yarn.points.push_back(p);
      yarn.stitch.push_back(s);
    }
    // At the end of a course the yarn climbs the selvedge to the next
    // course (the same yarn's next stitch is the Top neighbour): one more
    // point halfway up the exit side, in the fabric plane.
    if (oi + 1 < order.size() && mesh.stitches[order[oi + 1]].yarn == st.yarn && adj.next_in_course(s) < 0) {
      const double u = st.direction < 0 ? 0.0 : 1.0;
      const Vec2 c = square_to_canonical(st.type, u, 0.55);
      const auto w = canonical_weights(st.type, c.x(), c.y());
      Vec3 p = Vec3::Zero();
      for (int i = 0; i < k; ++i) p += w[i] * corner[i];
      yarn.points.push_back(p);
      yarn.stitch.push_back(s);
    }
    last_of_yarn[yi] = s;
  }
  // Close every yarn with the exit point of its last stitch.
  for (size_t yi = 0; yi < model.yarns.size(); ++yi) {
    const int s = last_of_yarn[yi];
    const Stitch& st = mesh.stitches[s];
    Variant var{st.type, static_cast<uint8_t>(st.roles & 15), st.direction < 0, false};
    if (st.roles & (kRoleOutsideIncrease | kRoleOutsideDecrease)) {
      var.open_left = adj.neighbor(s, Side::Left) < 0 || adj.neighbor(s, Side::Right) >= 0;
    }
    const std::vector<Weighted>& pts = cache[var.key()];
    const Vec3 nrm = radius * facet_normal(mesh, st);
    Vec3 p = pts.back().z * nrm;
    for (int i = 0; i < st.corners(); ++i) p += pts.back().w[i] * mesh.vertices[st.v[i]];
    model.yarns[yi].points.push_back(p);
    model.yarns[yi].stitch.push_back(s);
  }
  return model;
}

}  // namespace knitforge
