#pragma once
/// \file cut_to_disk.h
/// Seams: cutting a surface that is not a disk into one, so that the design
/// routes (which knit one sheet with one boundary) can take it. An annulus
/// (a tube, a cap with a face opening and a neck rim) gets one seam between
/// its two boundary loops, a surface with b loops b - 1 seams, and a
/// surface with handles (genus g > 0) a cut graph through them first. The
/// seams are what is sewn after knitting; they are outputs (positions and
/// lengths), so a user can see and check them.
///
/// Order of the cuts:
///  1. The user's own cuts (CutToDiskOptions::cuts), if any, as given.
///  2. Handles (genus > 0): a cut graph of 2g loops (Erickson and
///     Whittlesey's greedy system of loops: the shortest-path tree of the
///     mesh edges from the first boundary loop, or from vertex 0 of a
///     closed surface, and a maximum spanning tree of the dual edges by the
///     length of the loop each edge closes; the 2g edges in neither close
///     the loops). The boundary loops are capped by virtual vertices for
///     this step, so the loops may pass through a hole. Mesh-edge paths (no
///     straightening).
///  3. Boundary loops (genus 0, b > 1): one seam at a time between two
///     different loops, until one is left: a piece of the source curve
///     (CutToDiskOptions::source) that runs from one loop to another when
///     there is one (garments put seams on their symmetry plane, which is
///     the usual source; the shortest piece, or the longest for the first
///     seam with `longest_source_seam`), otherwise the shortest path on the
///     surface from the first loop (the one with the smallest vertex id) to
///     any other (exact polyhedral geodesic, geodesic_path_from_source()).
/// Each cut splits the mesh along its path (split_mesh_along_path()) and
/// cuts it open (cut_mesh_along_paths()); a seam therefore appears twice on
/// the boundary of the disk, its two lips at the same positions.
///
/// The source is carried over to the disk (CutToDisk::source): the mesh is
/// first split along the source's polylines, so that they are paths of mesh
/// vertices, which the cuts then keep or duplicate. A source polyline that
/// crosses a seam is broken there (one end on each lip). The parts of the
/// source that lie on a seam are dropped: the seam is then where the wales
/// of the two sides of the source meet (where the field is largest), which
/// is what a seam on the symmetry plane of a garment is for; only when
/// nothing else is left is the source kept on one lip of the seam (the
/// lip on the left of the seam's path). The carried source is signed
/// when it cuts the disk in two (source_sides()), with the sides oriented
/// like the input source's where it had any.
///
/// The input must be a valid surface (validate_surface() without errors) of
/// one connected component. Deterministic. Vertices of the input keep their
/// indices (copies and new vertices are appended), so vertex_origin maps
/// every disk vertex to the input vertex it stands for.

#include <string>
#include <vector>

#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"

namespace knitforge {

/// Options of cut_to_disk().
struct CutToDiskOptions {
  /// Curves on the surface carried over to the disk (CutToDisk::source),
  /// typically the geodesic source; may be empty.
  GeodesicSource source;
  /// Prefer pieces of the source between two boundary loops as seams (step
  /// 3 of the file comment).
  bool seams_on_source = true;
  /// The first loop seam follows the longest such piece of the source
  /// instead of the shortest. The short-row route asks for it: its wales
  /// run from the source to the seams, and on each side of the source a
  /// seam shorter than the source makes them crowd into it and meet at a
  /// ridge, which no course crosses (the built-in cap with the plane x = 0:
  /// a seam under the chin leaves the whole back of the head as the source,
  /// while a seam down the back leaves the short arc under the chin, from
  /// which the wales spread).
  bool longest_source_seam = false;
  /// The user's cuts (mm), cut first: polylines of 3D points put on the
  /// surface by surface_cut_from_polyline() (after the split along the
  /// source, so that cuts may cross it).
  std::vector<std::vector<Vec3>> cuts;
};

/// Why a seam was cut.
enum class SeamKind {
  User,    ///< one of CutToDiskOptions::cuts
  Handle,  ///< a branch of the cut graph through the handles (genus > 0)
  Loops,   ///< joins two boundary loops
};

/// "user", "handle", "loops".
const char* to_string(SeamKind kind);

/// One seam: a path on the input surface, cut open.
struct Seam {
  SeamKind kind = SeamKind::Loops;
  /// The seam follows a piece of the source curve (step 3).
  bool on_source = false;
  std::vector<Vec3> path;  ///< positions along the seam (mm)
  double length = 0.0;     ///< mm
};

/// The disk and how it was made.
struct CutToDisk {
  TriMesh mesh;  ///< the disk: one component, one boundary loop, genus 0
  /// For every vertex of `mesh`, the input vertex it is (a copy of), or -1
  /// for a vertex added by splitting (on an edge or inside a face).
  std::vector<int> vertex_origin;
  std::vector<Seam> seams;  ///< in cutting order
  /// The source carried over to the disk (empty polylines when the options
  /// had no source); see the file comment.
  GeodesicSource source;
  /// True when the carried source lies on a seam's lip (nothing else of the
  /// source was left).
  bool source_on_seam = false;
  /// Pieces of the source that joined two different boundary loops before
  /// the first loop seam was cut (the candidates for it).
  int source_seam_candidates = 0;
  int input_boundary_loops = 0;  ///< topology of the input
  int input_genus = 0;
};

/// Total length of the seams (mm).
double seam_length(const std::vector<Seam>& seams);

/// Cuts `mesh` into a disk (see the file comment). A disk without user cuts
/// is returned unchanged (no seams; the source as given).
/// \throw TopologyError naming the input (`what`) when it is not a valid
///        surface, has several connected components (design each part
///        separately), is a closed surface of genus 0 (it needs an opening:
///        remove the faces of one), or when the user's cuts leave several
///        pieces; InvalidInput for invalid cut or source points;
///        SolverError if the result is not a
///        disk (a bug).
CutToDisk cut_to_disk(const TriMesh& mesh, const CutToDiskOptions& options = {},
                      const std::string& what = "the surface");

/// A user's cut from 3D points (mm): each point goes to its closest surface
/// point and consecutive points are joined along the surface as a polyline
/// source is (source_from_polyline()). An end within one mean edge length
/// of the boundary is moved onto the nearest boundary point first, so that
/// a cut drawn "to the rim" reaches it (a cut that stops just short of the
/// rim would leave a slit and a hole instead of joining the loops).
/// \throw InvalidInput as source_from_polyline().
std::vector<SurfacePoint> surface_cut_from_polyline(const TriMesh& mesh, const std::vector<Vec3>& points);

}  // namespace knitforge
