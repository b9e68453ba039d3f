#include "knitforge/design/shortrow/wale_curves.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "knitforge/geometry/cut_mesh_along_path.h"
#include "knitforge/geometry/geodesic_path.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/resample_polyline.h"
#include "knitforge/geometry/split_mesh_along_path.h"
#include "knitforge/util/errors.h"

namespace knitforge {

int WaleCurves::num_wales() const {
  int n = 0;
  for (const auto& l : wales) n += static_cast<int>(l.size());
  return n;
}

namespace {

/// The vertex of the local extremum enclosed by a closed isocurve: of the two
/// sides of the curve (F above and below the level), the one whose component
/// of same-sign vertices touches no boundary is the inside; its most extreme
/// vertex is returned, or -1 when both sides reach the boundary.
int enclosed_extremum(const TriMesh& mesh, const Halfedges& he, const std::vector<double>& field,
                      const Isocurve& curve) {
  const int nv = mesh.num_vertices();
  for (int side : {+1, -1}) {
    std::vector<int> seeds;
    for (const MeshPoint& p : curve.points) {
      if (!p.is_edge()) continue;
      for (int v : {p.v0, p.v1}) {
        if ((field[v] - curve.value) * side > 0) seeds.push_back(v);
      }
    }
    if (seeds.empty()) continue;
    std::vector<char> seen(nv, 0);
    std::deque<int> queue;
    for (int v : seeds) {
      if (!seen[v]) {
        seen[v] = 1;
        queue.push_back(v);
      }
    }
    bool touches_boundary = false;
    int best = -1;
    while (!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      if (he.is_boundary_vertex(v)) touches_boundary = true;
      if (best < 0 || field[v] * side > field[best] * side || (field[v] == field[best] && v < best)) best = v;
      for (int w : he.vertex_neighbors(v)) {
        if (!seen[w] && (field[w] - curve.value) * side > 0) {
          seen[w] = 1;
          queue.push_back(w);
        }
      }
    }
    if (!touches_boundary) return best;
  }
  return -1;
}

// True when every point of the curve lies within `delta` of one cut's path.
bool hugs_a_cut(const Isocurve& curve, const std::vector<WaleCut>& cuts, double delta) {
  for (const WaleCut& cut : cuts) {
    bool all = true;
    for (const Vec3& p : curve.positions) {
      bool near = false;
      for (size_t k = 0; k + 1 < cut.path.size() && !near; ++k) {
        near = (closest_point_on_segment(p, cut.path[k], cut.path[k + 1]) - p).squaredNorm() <= delta * delta;
      }
      if (!near) {
        all = false;
        break;
      }
    }
    if (all) return true;
  }
  return false;
}

// True when a piece of the level is closed or hugs a cut.
bool degenerate_level(const std::vector<Isocurve>& level, const std::vector<WaleCut>& cuts, double delta) {
  for (const Isocurve& c : level) {
    if (c.closed || hugs_a_cut(c, cuts, delta)) return true;
  }
  return false;
}

MeshPoint to_mesh_point(const GeodesicPathPoint& p) {
  if (p.is_face_point())
    return MeshPoint::in_face(p.point.face, {p.point.bary[0], p.point.bary[1], p.point.bary[2]});
  if (p.is_vertex()) return MeshPoint::at_vertex(p.v0);
  return MeshPoint::on_edge(p.v0, p.v1, p.ratio);
}

}  // namespace

WaleCurves compute_wale_curves(const TriMesh& mesh, const std::vector<double>& field,
                               const KnitParams& params, const WaleOptions& options) {
  const double sw = params.stitch_width, sh = params.stitch_height;
  if (!(sw > 0.0) || !(sh > 0.0) || !std::isfinite(sw) || !std::isfinite(sh)) {
    throw InvalidInput(fmt::format("wale curves: stitch size {} x {} mm must be positive", sw, sh));
  }
  if (static_cast<int>(field.size()) != mesh.num_vertices()) {
    throw InvalidInput(fmt::format("wale curves: the field has {} values for {} vertices", field.size(),
                                   mesh.num_vertices()));
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::vector<char> used(mesh.num_vertices(), 0);
  for (const auto& t : mesh.faces) {
    for (int v : t) used[v] = 1;
  }
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!used[v]) continue;
    if (!std::isfinite(field[v])) {
      throw InvalidInput(fmt::format("wale curves: field value of vertex {} is not finite", v));
    }
    lo = std::min(lo, field[v]);
    hi = std::max(hi, field[v]);
  }
  if (!(hi - lo >= sw)) {
    throw InvalidInput(
        fmt::format("wale curves: the field spans {:.4g} mm, less than one stitch width ({} mm): the surface "
                    "is too narrow "
                    "across the wales for two wale curves; use a smaller stitch or another source",
                    hi - lo, sw));
  }

  WaleCurves out;
  out.surface = mesh;
  out.field = field;
  out.values = isocurve_levels(std::ceil(lo / sw - 1e-9) * sw, hi, sw);

  std::vector<std::vector<Isocurve>> curves;
  for (int round = 0;; ++round) {
    curves = extract_isocurves(out.surface, out.field, out.values);
    // The first closed isocurve that encloses a local extremum. A closed
    // curve with no such interior (e.g. a source along the whole boundary
    // loop) is opened by the cuts the others ask for, or reported below.
    const Isocurve* closed = nullptr;
    const Isocurve* first_closed = nullptr;
    int peak = -1;
    std::optional<Halfedges> he;
    for (const auto& level : curves) {
      for (const auto& c : level) {
        if (!c.closed) continue;
        if (!first_closed) first_closed = &c;
        if (!he) he = build_halfedges(out.surface.num_vertices(), out.surface.faces);
        peak = enclosed_extremum(out.surface, *he, out.field, c);
        if (peak >= 0) {
          closed = &c;
          break;
        }
      }
      if (closed) break;
    }
    if (!first_closed) break;
    if (!closed) {
      const Vec3 where = first_closed->positions.front();
      throw TopologyError(fmt::format(
          "wale curves: the isocurve F = {:.4g} mm near ({:.4g}, {:.4g}, {:.4g}) is closed but encloses no "
          "region without boundary, so no cut to the boundary can open it; is the surface a disk, and is the "
          "source the whole boundary loop? Use part of the boundary (--source boundary:0,0.5) or cut the "
          "surface "
          "open (--cut)",
          first_closed->value, where.x(), where.y(), where.z()));
    }
    const Vec3 where = closed->positions.front();
    if (round >= options.max_cuts) {
      throw TopologyError(
          fmt::format("wale curves: the isocurve F = {:.4g} mm near ({:.4g}, {:.4g}, {:.4g}) is still closed "
                      "after {} cuts; "
                      "the field has too many local extrema: choose another source",
                      closed->value, where.x(), where.y(), where.z(), options.max_cuts));
    }
    const GeodesicPath path =
        geodesic_path_to_boundary(out.surface, surface_point_at_vertex(out.surface, peak));
    std::vector<MeshPoint> points;
    for (const auto& p : path.points) points.push_back(to_mesh_point(p));
    WaleCut cut;
    cut.level_value = closed->value;
    cut.extremum = out.surface.vertices[peak];
    for (const auto& p : path.points) cut.path.push_back(p.position);
    cut.length = path.length;

    const SplitMeshResult split = split_mesh_along_path(out.surface, points);
    const std::vector<double> split_field = carry_vertex_scalar(out.surface, split, out.field);
    if (split.path.size() < 2) {
      throw TopologyError(fmt::format(
          "wale curves: the cut from the extremum at ({:.4g}, {:.4g}, {:.4g}) to the boundary is degenerate",
          cut.extremum.x(), cut.extremum.y(), cut.extremum.z()));
    }
    const CutMeshResult opened = cut_mesh_along_path(split.mesh, split.path);
    std::vector<double> opened_field(opened.mesh.num_vertices());
    for (int v = 0; v < opened.mesh.num_vertices(); ++v)
      opened_field[v] = split_field[opened.vertex_origin[v]];
    out.surface = opened.mesh;
    out.field = std::move(opened_field);
    out.cuts.push_back(std::move(cut));
  }

  // Levels through a saddle of F on a cut (see the header): move them by a
  // fraction of sw until no piece runs along the cut.
  if (!out.cuts.empty() && options.max_level_shift > 0) {
    // A piece along a cut runs through the faces next to it: within about one
    // edge of the cut's path (which crosses those faces) plus the allowance.
    const double delta = options.cut_hug_fraction * sw + edge_length_stats(out.surface).mean;
    for (size_t l = 0; l < curves.size(); ++l) {
      if (!degenerate_level(curves[l], out.cuts, delta)) continue;
      const double v = out.values[l];
      const double below = l > 0 ? out.values[l - 1] : -std::numeric_limits<double>::infinity();
      const double above = l + 1 < out.values.size() ? out.values[l + 1] : std::numeric_limits<double>::infinity();
      // Shifts of k/4 x max_level_shift x sw, smallest first, + before -.
      const int steps = 4;
      bool shifted = false;
      for (int k = 1; k <= steps && !shifted; ++k) {
        for (double sign : {1.0, -1.0}) {
          const double shift = sign * k * options.max_level_shift * sw / steps;
          const double w = v + shift;
          if (!(w - below > 0.5 * sw && above - w > 0.5 * sw)) continue;
          std::vector<std::vector<Isocurve>> moved = extract_isocurves(out.surface, out.field, {w});
          if (degenerate_level(moved[0], out.cuts, delta)) continue;
          out.values[l] = w;
          curves[l] = std::move(moved[0]);
          out.shifted_levels.push_back({static_cast<int>(l), shift});
          shifted = true;
          break;
        }
      }
    }
  }

  out.wales.resize(out.values.size());
  for (size_t l = 0; l < curves.size(); ++l) {
    for (const Isocurve& c : curves[l]) {
      const double len = c.length();
      if (c.positions.size() < 2 || len < options.min_length_fraction * sh) {
        ++out.dropped_pieces;
        continue;
      }
      // Long wales take the nearest even number of equal segments (within
      // sh / n of the stitch height, on the surface); short ones, where that
      // would stretch or squeeze their few segments a lot, are extended at
      // both ends as the seed does (see the header).
      ResampleOptions ro;
      ro.extend_ends = len < options.extend_below * sh;
      const ResampledPolyline r = resample_polyline(c.positions, sh, ro);
      WaleCurve w;
      w.level = static_cast<int>(l);
      w.value = out.values[l];
      w.points = r.points;
      w.isocurve = c.positions;
      w.length = len;
      w.extension = r.extension;
      out.wales[l].push_back(std::move(w));
    }
  }
  return out;
}

}  // namespace knitforge
