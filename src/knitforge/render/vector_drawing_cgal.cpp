// Algorithm 1.2 (seed §1.A.2) with CGAL's 2D arrangements. Named *_cgal.cpp
// because it instantiates Arrangement_2 (compiled uninstrumented in
// sanitizer builds).
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include <CGAL/Arr_batched_point_location.h>
#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <fmt/core.h>

#include "knitforge/render/projected_triangle_index.h"
#include "knitforge/render/vector_drawing.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using SegmentTraits = CGAL::Arr_segment_traits_2<Kernel>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegmentTraits, int>;
using Dcel = CGAL::Arr_face_extended_dcel<Traits, int>;
using Arrangement = CGAL::Arrangement_2<Traits, Dcel>;
using Point = Traits::Point_2;

// A projected contour segment: NDC end points (z = depth).
struct Contour {
  Vec3 a, b;
  int mesh;
  bool boundary;
};

// Triangle of the front-facing scene: which mesh and face it came from.
struct FrontFace {
  int mesh, face;
};

Vec2 to_vec2(const Point& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

// Depth of contour c at the image point m (m on or next to its projection).
double contour_depth(const Contour& c, const Vec2& m) {
  const Vec2 a = c.a.head<2>(), d = c.b.head<2>() - a;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((m - a).dot(d) / l2, 0.0, 1.0) : 0.0;
  return c.a.z() + t * (c.b.z() - c.a.z());
}

RenderColour colour_of(const RenderMesh& m, int face, const Vec3& bary) {
  if (!m.face_colours.empty()) return m.face_colours[static_cast<size_t>(face)];
  if (!m.vertex_colours.empty()) {
    const auto& f = m.mesh.faces[static_cast<size_t>(face)];
    RenderColour out{};
    for (int ch = 0; ch < 3; ++ch) {
      double v = 0.0;
      for (int k = 0; k < 3; ++k)
        v += bary[k] *
             m.vertex_colours[static_cast<size_t>(f[static_cast<size_t>(k)])][static_cast<size_t>(ch)];
      out[static_cast<size_t>(ch)] = static_cast<uint8_t>(std::clamp(std::lround(v), 0L, 255L));
    }
    return out;
  }
  return m.colour;
}

template <class Ccb>
std::vector<Vec2> ring_of(Ccb first) {
  std::vector<Vec2> ring;
  Ccb c = first;
  do {
    ring.push_back(to_vec2(c->source()->point()));
  } while (++c != first);
  return ring;
}

}  // namespace

VectorDrawing vector_drawing(std::span<const RenderMesh> meshes, const Camera& camera) {
  const ViewTransform view = view_transform(camera);
  VectorDrawing out;
  out.aspect = camera.aspect;

  // 1-3: NDC, back-face removal, contour edges of M_f per mesh.
  std::vector<std::array<Vec3, 3>> front;
  std::vector<FrontFace> front_id;
  std::vector<Contour> contours;
  for (size_t mi = 0; mi < meshes.size(); ++mi) {
    const RenderMesh& m = meshes[mi];
    validate_render_mesh(m);
    const size_t nv = m.mesh.vertices.size();
    std::vector<Vec3> ndc(nv);
    std::vector<char> ok(nv);
    for (size_t v = 0; v < nv; ++v) {
      ok[v] = view.in_front(m.mesh.vertices[v]) ? 1 : 0;
      if (ok[v]) ndc[v] = view.to_ndc(m.mesh.vertices[v]);
    }
    // (min vertex, max vertex, is front face, face) for every face edge
    std::vector<std::tuple<int, int, int, int>> edges;
    edges.reserve(3 * m.mesh.faces.size());
    for (size_t f = 0; f < m.mesh.faces.size(); ++f) {
      const auto& t = m.mesh.faces[f];
      const bool visible_vertices =
          ok[static_cast<size_t>(t[0])] && ok[static_cast<size_t>(t[1])] && ok[static_cast<size_t>(t[2])];
      if (!visible_vertices) ++out.clipped_faces;
      bool is_front = false;
      if (visible_vertices) {
        const Vec3& a = ndc[static_cast<size_t>(t[0])];
        const Vec3& b = ndc[static_cast<size_t>(t[1])];
        const Vec3& c = ndc[static_cast<size_t>(t[2])];
        const double area2 = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
        is_front = area2 > 0.0;
        if (is_front) {
          front.push_back({a, b, c});
          front_id.push_back({static_cast<int>(mi), static_cast<int>(f)});
        }
      }
      for (int k = 0; k < 3; ++k) {
        const int u = t[static_cast<size_t>(k)], w = t[static_cast<size_t>((k + 1) % 3)];
        edges.emplace_back(std::min(u, w), std::max(u, w), is_front ? 1 : 0, static_cast<int>(f));
      }
    }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size();) {
      size_t j = i;
      int fronts = 0;
      while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
             std::get<1>(edges[j]) == std::get<1>(edges[i])) {
        fronts += std::get<2>(edges[j]);
        ++j;
      }
      if (fronts == 1) {
        const int u = std::get<0>(edges[i]), w = std::get<1>(edges[i]);
        contours.push_back(
            {ndc[static_cast<size_t>(u)], ndc[static_cast<size_t>(w)], static_cast<int>(mi), j - i == 1});
      }
      i = j;
    }
  }
  out.front_faces = static_cast<int>(front.size());

  double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
  for (const auto& t : front) {
    for (const Vec3& c : t) {
      zlo = std::min(zlo, c.z());
      zhi = std::max(zhi, c.z());
    }
  }
  const double eps =
      front.empty() ? 0.0
                    : 1e-6 * std::max(zhi - zlo, 1e-12 * std::max(std::abs(zlo), std::abs(zhi))) + 1e-300;
  const ProjectedTriangleIndex index(std::move(front));

  // 4: the arrangement of the projected contours.
  std::vector<Traits::Curve_2> curves;
  curves.reserve(contours.size());
  for (size_t i = 0; i < contours.size(); ++i) {
    const Point p(contours[i].a.x(), contours[i].a.y()), q(contours[i].b.x(), contours[i].b.y());
    if (p == q) continue;
    curves.emplace_back(SegmentTraits::Curve_2(p, q), static_cast<int>(i));
  }
  out.contour_segments = static_cast<int>(curves.size());
  Arrangement arr;
  CGAL::insert(arr, curves.begin(), curves.end());
  out.arrangement_edges = static_cast<int>(arr.number_of_edges());

  // 5: visibility by a ray through each edge's midpoint.
  std::vector<Arrangement::Halfedge_handle> hidden;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const Vec2 mid = 0.5 * (to_vec2(e->source()->point()) + to_vec2(e->target()->point()));
    const auto& data = e->curve().data();
    int best = -1;
    double depth = std::numeric_limits<double>::infinity();
    for (auto it = data.begin(); it != data.end(); ++it) {
      const double d = contour_depth(contours[static_cast<size_t>(*it)], mid);
      if (best < 0 || d < depth || (d == depth && *it < best)) {
        best = *it;
        depth = d;
      }
    }
    const auto hit = index.first_hit(mid);
    const bool visible = hit.triangle < 0 || hit.depth >= depth - eps;
    if (visible) {
      const Contour& c = contours[static_cast<size_t>(best)];
      out.edges.push_back({to_vec2(e->source()->point()), to_vec2(e->target()->point()), c.mesh, c.boundary});
    } else {
      hidden.push_back(e);
    }
  }
  out.hidden_edges = static_cast<int>(hidden.size());
  for (auto e : hidden) arr.remove_edge(e);

  // 6: colour each bounded face by a ray through an interior point. The
  // point is found next to a boundary edge (offset to its left, where the
  // face lies) and confirmed by batched point location.
  std::vector<Arrangement::Face_handle> faces;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    f->set_data(-1);
    if (f->is_unbounded() || !f->has_outer_ccb()) continue;
    f->set_data(static_cast<int>(faces.size()));
    faces.push_back(f);
  }
  std::vector<std::vector<Arrangement::Halfedge_handle>> candidates(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    auto first = faces[i]->outer_ccb();
    auto c = first;
    do {
      if (c->twin()->face() != c->face()) candidates[i].push_back(c);
    } while (++c != first);
    if (candidates[i].empty()) candidates[i].push_back(first);
    std::stable_sort(candidates[i].begin(), candidates[i].end(), [](const auto& a, const auto& b) {
      return (to_vec2(a->target()->point()) - to_vec2(a->source()->point())).squaredNorm() >
             (to_vec2(b->target()->point()) - to_vec2(b->source()->point())).squaredNorm();
    });
    if (candidates[i].size() > 4) candidates[i].resize(4);
  }
  std::vector<Vec2> interior(faces.size());
  std::vector<char> found(faces.size(), 0);
  constexpr double kOffsets[] = {1e-2, 1e-4, 1e-6, 1e-8};
  for (int attempt = 0; attempt < 16; ++attempt) {
    std::vector<Point> queries;
    std::vector<int> query_face;
    for (size_t i = 0; i < faces.size(); ++i) {
      if (found[i]) continue;
      const size_t hc = static_cast<size_t>(attempt % 4);
      if (hc >= candidates[i].size()) continue;
      const auto h = candidates[i][hc];
      const Vec2 a = to_vec2(h->source()->point()), b = to_vec2(h->target()->point());
      const Vec2 d = b - a;
      const Vec2 p = 0.5 * (a + b) + kOffsets[attempt / 4] * Vec2(-d.y(), d.x());
      queries.emplace_back(p.x(), p.y());
      query_face.push_back(static_cast<int>(i));
    }
    if (queries.empty()) break;
    std::vector<std::pair<Point, CGAL::Arr_point_location_result<Arrangement>::Type>> located;
    CGAL::locate(arr, queries.begin(), queries.end(), std::back_inserter(located));
    for (const auto& [pt, res] : located) {
      const auto* f = boost::get<Arrangement::Face_const_handle>(&res);
      if (!f) continue;
      const int id = (*f)->data();
      if (id < 0 || found[static_cast<size_t>(id)]) continue;
      // a face located at a query meant for another face is fine too
      found[static_cast<size_t>(id)] = 1;
      interior[static_cast<size_t>(id)] = to_vec2(pt);
    }
  }
  for (size_t i = 0; i < faces.size(); ++i) {
    if (!found[i]) continue;  // no interior point found (a sliver below 1e-8 NDC); left unfilled
    const auto hit = index.first_hit(interior[i]);
    if (hit.triangle < 0) continue;
    const FrontFace& ff = front_id[static_cast<size_t>(hit.triangle)];
    DrawingRegion r;
    r.mesh = ff.mesh;
    r.colour = colour_of(meshes[static_cast<size_t>(ff.mesh)], ff.face, hit.barycentric);
    r.rings.push_back(ring_of(faces[i]->outer_ccb()));
    for (auto h = faces[i]->inner_ccbs_begin(); h != faces[i]->inner_ccbs_end(); ++h)
      r.rings.push_back(ring_of(*h));
    out.regions.push_back(std::move(r));
  }
  return out;
}

}  // namespace knitforge
