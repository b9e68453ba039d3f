#include "knitforge/convert/relax_stitch_mesh.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/geometry/shape_up.h"
#include "knitforge/util/errors.h"

namespace knitforge {

std::vector<Vec3> ideal_stitch_shape(StitchType type, const KnitParams& p) {
  const double w = p.stitch_width, h = p.stitch_height;
  // Short-row ends: legs of length w over a base of length h.
  const double sr = std::sqrt(std::max(w * w - 0.25 * h * h, 0.0));
  // Increases / decreases: legs of length h over a base of length w.
  const double sc = h * h > 0.25 * w * w ? std::sqrt(h * h - 0.25 * w * w) : 0.5 * h;
  switch (type) {
    case StitchType::Knit: return {Vec3(0, 0, 0), Vec3(w, 0, 0), Vec3(w, h, 0), Vec3(0, h, 0)};
    case StitchType::ShortRowLeft: return {Vec3(w - sr, h / 2, 0), Vec3(w, 0, 0), Vec3(w, h, 0)};
    case StitchType::ShortRowRight: return {Vec3(0, 0, 0), Vec3(sr, h / 2, 0), Vec3(0, h, 0)};
    case StitchType::Increase: return {Vec3(w / 2, h - sc, 0), Vec3(w, h, 0), Vec3(0, h, 0)};
    case StitchType::Decrease: return {Vec3(0, 0, 0), Vec3(w, 0, 0), Vec3(w / 2, sc, 0)};
  }
  throw InvalidInput(fmt::format("unknown stitch type {}", static_cast<int>(type)));
}

namespace {

/// The hinge polygon of stitches a and b sharing the edge {u, v} (see
/// RelaxOptions::bending): the corners of a, then those of b that a lacks,
/// with targets in a's frame, b's ideal shape turned and moved so that its
/// copy of the shared edge lies on a's (matched at the midpoint, along the
/// edge direction); b then lies on the other side of the edge because both
/// stitches run counter-clockwise.
void add_hinge(const StitchMesh& mesh, int a, int b, int u, int v, const std::vector<Vec3> shapes[],
               double weight, ShapeUpPolygons& poly) {
  const Stitch& sa = mesh.stitches[a];
  const Stitch& sb = mesh.stitches[b];
  const std::vector<Vec3>& ta = shapes[static_cast<int>(sa.type)];
  const std::vector<Vec3>& tb = shapes[static_cast<int>(sb.type)];
  auto corner = [](const Stitch& s, int vertex) {
    for (int k = 0; k < s.corners(); ++k) {
      if (s.v[k] == vertex) return k;
    }
    return -1;
  };
  const int au = corner(sa, u), av = corner(sa, v), bu = corner(sb, u), bv = corner(sb, v);
  const Eigen::Vector2d ea = (ta[av] - ta[au]).head<2>(), eb = (tb[bv] - tb[bu]).head<2>();
  if (!(ea.norm() > 0 && eb.norm() > 0)) return;
  const double angle = std::atan2(ea.y(), ea.x()) - std::atan2(eb.y(), eb.x());
  const Eigen::Rotation2Dd rot(angle);
  const Eigen::Vector2d mid_a = 0.5 * (ta[au] + ta[av]).head<2>(), mid_b = 0.5 * (tb[bu] + tb[bv]).head<2>();
  std::vector<int> vertices;
  std::vector<Vec3> targets;
  for (int k = 0; k < sa.corners(); ++k) {
    vertices.push_back(sa.v[k]);
    targets.push_back(ta[k]);
  }
  for (int k = 0; k < sb.corners(); ++k) {
    if (corner(sa, sb.v[k]) >= 0) continue;
    const Eigen::Vector2d q = rot * (tb[k].head<2>() - mid_b) + mid_a;
    vertices.push_back(sb.v[k]);
    targets.emplace_back(q.x(), q.y(), 0.0);
  }
  poly.add(vertices, targets, weight);
}

}  // namespace

RelaxResult relax_stitch_mesh(const StitchMesh& mesh, const KnitParams& params, const RelaxOptions& options) {
  if (!(std::isfinite(params.stitch_width) && params.stitch_width > 0 && std::isfinite(params.stitch_height) &&
        params.stitch_height > 0)) {
    throw InvalidInput(fmt::format("stitch size {} x {} mm: both must be finite and > 0", params.stitch_width,
                                   params.stitch_height));
  }
  if (options.max_iterations < 0 || options.anderson_depth < 0 || !(options.tolerance >= 0) || !(std::isfinite(options.warm_up) && options.warm_up >= 0) ||
      !(std::isfinite(options.bending) && options.bending >= 0)) {
    throw InvalidInput(fmt::format("relax options: max_iterations {} must be >= 0, tolerance {} >= 0, warm_up {} "
                                   "and bending {} finite and >= 0",
                                   options.max_iterations, options.tolerance, options.warm_up, options.bending));
  }
  if (mesh.stitches.empty()) throw InvalidInput("relax_stitch_mesh: the stitch mesh has no stitches");
  const int nv = mesh.num_vertices();
  for (int v = 0; v < nv; ++v) {
    if (!mesh.vertices[v].allFinite()) throw InvalidInput(fmt::format("stitch mesh vertex {} has a non-finite position", v));
  }
  std::vector<Vec3> shapes[kNumStitchTypes];
  double area[kNumStitchTypes];
  for (int t = 0; t < kNumStitchTypes; ++t) {
    shapes[t] = ideal_stitch_shape(static_cast<StitchType>(t), params);
    area[t] = 0;  // eq. 1.1 weight: the area of the ideal shape (shoelace formula)
    for (size_t k = 0; k < shapes[t].size(); ++k) {
      const Vec3& a = shapes[t][k];
      const Vec3& b = shapes[t][(k + 1) % shapes[t].size()];
      area[t] += 0.5 * (a.x() * b.y() - b.x() * a.y());
    }
  }
  ShapeUpPolygons poly;
  poly.vertices.reserve(4 * mesh.stitches.size());
  poly.targets.reserve(4 * mesh.stitches.size());
  poly.weights.reserve(mesh.stitches.size());
  poly.start.reserve(mesh.stitches.size() + 1);
  bool shaped = false;
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    if (static_cast<int>(st.type) >= kNumStitchTypes) {
      throw TopologyError(fmt::format("stitch {} has an unknown type {}", s, static_cast<int>(st.type)));
    }
    const int n = st.corners();
    for (int k = 0; k < n; ++k) {
      if (st.v[k] < 0 || st.v[k] >= nv) {
        throw TopologyError(fmt::format("stitch {} corner {} is vertex {} (valid: 0..{})", s, k, st.v[k], nv - 1));
      }
      for (int l = 0; l < k; ++l) {
        if (st.v[l] == st.v[k]) throw TopologyError(fmt::format("stitch {} uses vertex {} twice", s, st.v[k]));
      }
      poly.vertices.push_back(st.v[k]);
      poly.targets.push_back(shapes[static_cast<int>(st.type)][k]);
    }
    poly.weights.push_back(area[static_cast<int>(st.type)]);
    poly.start.push_back(static_cast<int>(poly.vertices.size()));
    shaped = shaped || is_shaping(st.type);
  }

  if (options.bending > 0) {
    // One hinge per pair of stitches sharing an edge, in the order the
    // half-edge of the later stitch comes.
    const StitchAdjacency adjacency(mesh);
    const Halfedges& he = adjacency.halfedges();
    for (int h = 0; h < he.num_halfedges(); ++h) {
      const int o = he.opposite(h);
      if (o < 0 || o > h) continue;
      const int first = he.face(o), second = he.face(h);
      const double w = options.bending * 0.5 * (area[static_cast<int>(mesh.stitches[first].type)] +
                                                area[static_cast<int>(mesh.stitches[second].type)]);
      add_hinge(mesh, first, second, he.from(h), he.to(h), shapes, w, poly);
    }
  }

  std::vector<Vec3> start = mesh.vertices;
  // A mesh without shaping stitches is developable and its flat layout already
  // has zero energy; the warm-up only matters (seed Fig. 1.5) for shaped ones.
  if (options.warm_up > 0 && shaped && nv > 0) {
    Eigen::Vector2d lo = start[0].head<2>(), hi = lo;
    for (const Vec3& p : start) {
      lo = lo.cwiseMin(p.head<2>());
      hi = hi.cwiseMax(p.head<2>());
    }
    const Eigen::Vector2d size = hi - lo;
    const double diag = size.norm();
    if (diag > 0) {
      for (Vec3& p : start) {
        const double u = size.x() > 0 ? 2 * (p.x() - lo.x()) / size.x() - 1 : 0.0;
        const double v = size.y() > 0 ? 2 * (p.y() - lo.y()) / size.y() - 1 : 0.0;
        p.z() += options.warm_up * diag * (1 - u * u) * (1 - v * v);
      }
    }
  }

  const ShapeUpSolver solver(nv, std::move(poly));
  ShapeUpOptions so;
  so.max_iterations = options.max_iterations;
  so.tolerance = options.tolerance;
  so.anderson_depth = options.anderson_depth;
  ShapeUpResult r = solver.solve(std::move(start), so);

  RelaxResult out;
  out.mesh = mesh;
  out.mesh.vertices = std::move(r.positions);
  out.energy = std::move(r.energy);
  out.iterations = r.iterations;
  out.converged = r.converged;
  return out;
}

}  // namespace knitforge
