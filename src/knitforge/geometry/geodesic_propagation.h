#pragma once
/// \file geodesic_propagation.h
/// The engine behind geodesic_distance() and geodesic_path(): exact window
/// propagation on a triangle mesh from point and segment sources lying on the
/// surface. Library-internal (namespace detail); use geodesic_distance.h and
/// geodesic_path.h.
///
/// Method (Xin & Wang 2009, "Improving Chen and Han's algorithm on the
/// discrete geodesic problem", extended to segment sources as in the
/// polyline-sourced MMP of seed §3.A.1 [16]): a window is an interval of a
/// mesh edge together with the unfolded source of the straight rays that
/// cross it, either a point (pseudo-source S, offset sigma: distance
/// |x - S| + sigma) or a segment interior (parallel rays: distance n·x + c).
/// Windows are processed in order of their smallest distance; a window is
/// propagated across the next face into at most two child windows, and a
/// child is dropped when one vertex of the two faces at its edge already
/// gives a shorter path to every point of it (the filter of Xin & Wang, with
/// bounds that are valid for any point of the interval). A window is also
/// trimmed to the part of its interval where neither end vertex of its edge
/// gives a shorter path (exact: the distance minus the distance along the
/// edge from an end is monotone over the interval, so the dominated part is
/// a sub-interval at that end whose limit solves a linear or quadratic
/// equation). Vertices whose total
/// angle is at least 2π (saddles, flat vertices), boundary vertices with an
/// angle of at least π, and vertices at degenerate faces emit new point
/// windows (geodesics can pass through them). Vertex distances are also
/// relaxed along edges (upper bounds that keep the filter effective and make
/// degenerate, zero-length edges harmless). The distances are exact
/// polyhedral distances up to rounding (1e-11 of the mesh size).
///
/// Windows that touch on an edge and carry the same distance function (same
/// root, same unfolding) are merged, so a wavefront that vertices split into
/// pieces does not fragment further on flat parts. Pieces split at a vertex
/// share an unfolding again only if that vertex is flat, so merge candidates
/// are looked for only on the half-edges next to flat vertices
/// (GeodesicGeometry::mergeable); merging never changes a distance, it only
/// saves work. The queue is a radix heap (keys grow monotonically) holding
/// copies of the windows, so processing a window reads no scattered memory.
/// Approximate mode (tolerance > 0, GeodesicOptions::tolerance): every new
/// window is also trimmed exactly against the windows already on its
/// half-edge (a compact per-half-edge index; pending windows it beats are
/// trimmed or killed), and touching parallel-family windows are merged into a
/// fitted family (merge_adjacent()). Tracing (trace_vertex() etc.) through a
/// fitted window is not reliable (lengths off by up to ~1 mm were measured),
/// so the path functions use the exact mode only.
/// Profile and measured speed: docs/geometry.md. Every window remembers its
/// root (seed or pseudo-source vertex); a shortest path is traced back from
/// any vertex, boundary point or face point by walking the window's straight
/// backward ray face by face in the unfolding.

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "knitforge/geometry/geodesic_path.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/halfedges.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge::detail {

/// Per-mesh data reused by every propagation (the part of the work that does
/// not depend on the source).
struct GeodesicGeometry {
  const TriMesh* mesh = nullptr;
  Halfedges he;
  std::vector<double> len;  ///< per half-edge: edge length
  std::vector<Vec2>
      apex;  ///< per half-edge h: the third vertex of face(h) in the frame from(h) = (0,0), to(h) = (len,0)
  std::vector<int>
      out_start;  ///< CSR: half-edges leaving vertex v are out_he[out_start[v] .. out_start[v+1])
  std::vector<int> out_he;
  std::vector<char> emits;           ///< per vertex: may act as a pseudo-source
  std::vector<char> degenerate;      ///< per vertex: touches a degenerate face or zero-length edge
  std::vector<double> corner_angle;  ///< per half-edge: the face's angle at from(h)
  std::vector<double> theta;         ///< per half-edge: angular position of from(h)->to(h) around from(h)
  std::vector<double> total_angle;   ///< per vertex: sum of its corner angles
  std::vector<char> is_boundary;     ///< per vertex
  /// Per half-edge h: a vertex of face(h) or of the face across h is
  /// intrinsically flat (interior, total angle 2π within 1e-9), so windows on
  /// h can meet pieces with the same distance function (split at that vertex)
  /// and are worth merging. Elsewhere the pieces of a window that meet again
  /// went around curved vertices and never share an unfolding.
  std::vector<char> mergeable;
  double scale = 1.0;  ///< bounding-box diagonal (mm)
  double eps = 0.0;    ///< absolute distance tolerance (1e-11 scale)
  /// Fraction of the interior vertices that emit (saddles, vertices at
  /// degenerate faces); 0 when there are no interior vertices.
  double saddle_fraction = 0.0;
};

/// Builds the geometry. \throw TopologyError from build_halfedges();
/// InvalidInput for non-finite coordinates or an empty mesh.
GeodesicGeometry build_geodesic_geometry(const TriMesh& mesh);

/// \throw InvalidInput when `p` is not a point of `mesh` (face out of range,
/// barycentric coordinates not >= 0 summing to 1).
void check_surface_point(const TriMesh& mesh, const SurfacePoint& p);

enum class Origin : char { None, Seed, Window, Vertex, Edge };

struct Window {
  int h = -1;                    ///< the window lies on edge(h) and propagates into face(h)
  bool line = false;             ///< segment-interior (parallel rays) instead of a point source
  bool done = false;             ///< propagated (set for windows on mergeable half-edges only, or all with a tolerance)
  bool dead = false;             ///< dropped after creation (approximate mode only: trimmed away by another window)
  char aux = 0;                  ///< seeds: 0 source point p, 1 source point q
  Origin origin = Origin::None;  ///< the root: Seed or Vertex (pseudo-source)
  int origin_id = -1;            ///< seed index or pseudo-source vertex
  double b0 = 0.0, b1 = 0.0;     ///< interval along h, from from(h)
  Vec2 s = Vec2::Zero();         ///< point: unfolded source (y < 0); line: unit ray direction (y > 0)
  double sigma = 0.0;            ///< point: offset; line: c in n·x + c
  double key = 0.0;              ///< smallest distance over the interval
};

/// A candidate end of a path: the best point found on the boundary.
struct BoundaryHit {
  double dist = std::numeric_limits<double>::infinity();
  int halfedge = -1;  ///< boundary half-edge (of the face it belongs to)
  double t = 0.0;     ///< position from(halfedge) + t (to - from)
  Origin origin = Origin::None;
  int origin_id = -1;  ///< window, vertex (emission or the boundary vertex itself) or seed
};

class GeodesicPropagation {
 public:
  /// `track_boundary`: also find the boundary point closest to the source
  /// (for trace_boundary()). `tolerance` (mm, >= 0): 0 is the exact
  /// propagation; > 0 enables the approximate window trimming described in
  /// geodesic_distance.h (GeodesicOptions::tolerance).
  explicit GeodesicPropagation(const GeodesicGeometry& g, bool track_boundary = false, double tolerance = 0.0);

  /// Adds the interior of segment p-q in every face that contains both.
  /// \throw InvalidInput when they share no face or a point is invalid (face
  /// out of range, barycentric coordinates not >= 0 summing to 1).
  void add_segment(const SurfacePoint& p, const SurfacePoint& q);
  /// Adds the point p in every face that contains it. `neighbours`: the
  /// adjacent points of p on its polyline (0, 1 or 2); the windows from p are
  /// restricted to the directions where p is the closest source point.
  void add_point(const SurfacePoint& p, const std::vector<const SurfacePoint*>& neighbours = {});

  /// Adds every point and segment of the source's polylines (a closed
  /// polyline, last point equal to the first, restricts its first point by
  /// both neighbours), as geodesic_distance() seeds its propagation.
  /// \throw as add_point() / add_segment().
  void add_source(const GeodesicSource& source);

  /// Side-restricted propagation (geodesic_distance.h, "two sides"): no
  /// window is kept on a half-edge h with (*blocked)[h] != 0 and no vertex
  /// distance is relaxed along such a half-edge. `blocked` has one entry per
  /// half-edge and must outlive run(); nullptr (the default) blocks nothing.
  /// The geometry is only read, so two propagations of one GeodesicGeometry
  /// (each with its own mask) may run concurrently in two threads.
  void set_blocked(const std::vector<char>* blocked) { blocked_ = blocked; }

  /// Propagates until every window is processed.
  void run();

  const std::vector<double>& distance() const { return dist_; }
  size_t num_windows() const { return windows_.size(); }
  const BoundaryHit& boundary_hit() const { return boundary_; }

  /// Shortest path from vertex v to the source, as points from v (first) to
  /// a source point (last).
  std::vector<GeodesicPathPoint> trace_vertex(int v) const;
  /// Shortest path from the best boundary point to the source.
  std::vector<GeodesicPathPoint> trace_boundary() const;
  /// Distance of a surface point and the path from it to the source.
  double trace_point(const SurfacePoint& p, std::vector<GeodesicPathPoint>* path) const;

 private:
  struct Seed {
    int face;
    Vec3 bp, bq;  // barycentric coordinates in face
    Vec2 p2, q2;  // in the frame of face_start(face)
  };
  struct QueueItem {
    double key;
    int id;    // >= 0 window, < 0: vertex -(id + 1)
    Window w;  // windows: a copy (processing it then reads no scattered memory)
  };
  /// Monotone priority queue (radix heap on the order-preserving bit pattern
  /// of the key): the keys pushed while an item is processed are never
  /// smaller than its key (distances grow along rays and edges); a key that
  /// rounding puts below the last popped one is treated as equal to it.
  class RadixQueue {
   public:
    bool empty() const { return size_ == 0; }
    void push(const QueueItem& item);
    QueueItem pop();  ///< \pre !empty()
   private:
    static uint64_t bits(double key);
    int bucket(uint64_t k) const;
    std::array<std::vector<QueueItem>, 65> buckets_;
    uint64_t last_ = 0;
    size_t size_ = 0;
  };
  /// A pending window in the merge candidates of its half-edge.
  struct PendingRef {
    uint32_t root;  ///< origin, origin_id, aux and line packed (root_code())
    int id;
    double sx, sigma;  ///< copies of the window's, to reject most candidates without reading it
  };
  static uint32_t root_code(const Window& w);
  /// Approximate mode: a compact copy of a live window of a half-edge (its
  /// interval and distance function), for the window-against-window trimming.
  struct IndexEntry {
    double b0, b1;
    Vec2 s;
    double sigma;
    int id;
    bool line;
  };
  /// Approximate mode: trims w against the windows already on its half-edge
  /// (and trims or kills pending ones that w makes redundant). False when
  /// nothing of w is left.
  bool trim_against_index(Window& w);
  /// The largest x in [lo, hi] with dist_o - dist_w <= 0 on [lo, x]
  /// (from_lo) or on [x, hi] (the smallest such x, !from_lo); returns lo
  /// (resp. hi) when the end itself is not dominated.
  bool merge_adjacent(const Window& w);
  double dominated_run(const IndexEntry& o, const IndexEntry& w, double lo, double hi, bool from_lo) const;

  void seed_face(int f, const Vec3& bp, const Vec3& bq, bool point, const std::vector<Vec2>& cons);
  void check_point(const SurfacePoint& p) const;
  /// Removes window `id` from the merge candidates of half-edge h.
  void unpend(int h, int id);
  void update_vertex(int v, double d, Origin origin, int id);
  bool prepare(Window& w) const;  // clamps the interval, sets the key; false when empty
  void push_window(const Window& w);
  /// Trims w to the part not dominated by the ends of its edge; true when
  /// nothing is left or a vertex of the faces at the edge dominates it all.
  bool dominated(Window& w, const Vec2* extra, int extra_vertex) const;
  void propagate(const Window& w, int wi);
  void emit_vertex(int v);
  double back_angle(int v) const;
  void make_child(const Window& parent, int wi, int k, double x0, double x1);
  void boundary_candidate(double d, int halfedge, double t, Origin origin, int id);

  double window_distance(const Window& w, const Vec2& x) const;
  double window_xint(const Window& w, const Vec2& x) const;
  Vec2 corner(int h, int k) const;
  GeodesicPathPoint edge_point(int h, double x) const;
  GeodesicPathPoint seed_point(int seed, const Vec3& from3d, int which, bool line) const;
  void trace_window_from(int wi, Vec2 x, std::vector<GeodesicPathPoint>& out) const;
  void trace_vertex_into(int v, std::vector<GeodesicPathPoint>& out) const;

  const GeodesicGeometry& g_;
  std::vector<double> dist_;
  std::vector<Origin> vorigin_;
  std::vector<int> vorigin_id_;
  std::vector<Window> windows_;
  /// Per half-edge: its pending windows, the candidates for merging
  /// (push_window()); contiguous, so the scan is cheap.
  std::vector<std::vector<PendingRef>> pending_;
  /// Approximate mode: per half-edge, the windows on it (IndexEntry).
  std::vector<std::vector<IndexEntry>> index_;
  double merge_slack_ = 0.0;  ///< approximate mode: largest deviation a merge may introduce (mm)
  bool approx_ = false;  ///< approximate mode (tolerance > 0)
  const std::vector<char>* blocked_ = nullptr;  ///< per half-edge: drop windows there (set_blocked())
  std::vector<Seed> seeds_;
  RadixQueue queue_;
  BoundaryHit boundary_;
  bool track_boundary_ = false;
};

}  // namespace knitforge::detail
