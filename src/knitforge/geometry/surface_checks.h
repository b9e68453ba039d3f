#pragma once
/// \file surface_checks.h
/// Repair-free validation of an input surface (TriMesh) with exact
/// diagnostics, and the disk-topology precondition most design routes need
/// (the surfaces of seed ch. 2 and §3 are disk-like patches).
///
/// Unlike build_halfedges(), which throws on the first topology problem,
/// validate_surface() never throws: it lists every problem with the index of
/// the element involved, so a user can fix the mesh in one go.

#include <string>
#include <string_view>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// The kinds of problem validate_surface() detects.
enum class SurfaceIssueKind {
  NonFiniteVertex,          ///< a coordinate is NaN or infinite (error; element = vertex)
  IndexOutOfRange,          ///< a face uses a vertex index outside [0, n) (error; element = face)
  RepeatedVertex,           ///< a face uses the same vertex twice (error; element = face)
  DegenerateFace,           ///< (near-)zero area (warning; element = face)
  ShortEdge,                ///< (near-)zero length edge (warning; element = face, vertices = the edge)
  DuplicateFace,            ///< same vertex set as an earlier face (error; element = face, other = earlier face)
  NonManifoldEdge,          ///< an edge used by more than two faces (error; vertices = the edge)
  NonManifoldVertex,        ///< the faces around a vertex form several fans (error; element = vertex)
  InconsistentOrientation,  ///< two faces use an edge in the same direction (error; element, other = faces)
  IsolatedVertex,           ///< a vertex used by no face (warning; element = vertex)
};

/// Human-readable name of a kind ("non-manifold edge", ...).
std::string_view to_string(SurfaceIssueKind kind);

/// One problem found by validate_surface().
struct SurfaceIssue {
  SurfaceIssueKind kind{};
  bool is_error = true;   ///< false: a warning (the mesh is still usable)
  int element = -1;      ///< the vertex or face index the kind names, -1 if none
  int other = -1;        ///< a second face (duplicate / orientation), -1 if none
  int vertex_a = -1;     ///< edge endpoints (short / non-manifold edges), -1 if none
  int vertex_b = -1;
  std::string message;   ///< full sentence naming the elements and what to do
};

/// Thresholds of the warnings, relative to the mean edge length L of the mesh.
struct SurfaceCheckOptions {
  /// A face is degenerate when twice its area is below this times its longest
  /// edge squared (its height is below this fraction of its longest edge).
  double degenerate_face_ratio = 1e-8;
  /// An edge is near-zero when shorter than this times L.
  double short_edge_ratio = 1e-6;
};

/// Everything validate_surface() found, plus the topology summary.
///
/// The topology summary is computed on the faces without a per-face error
/// (out-of-range index, repeated vertex, duplicate) and on the vertices those
/// faces use. Boundary loops and genus are only meaningful for a manifold,
/// consistently oriented mesh (`manifold` true); otherwise num_boundary_loops
/// and genus are -1 and is_disk is false.
struct SurfaceReport {
  std::vector<SurfaceIssue> issues;  ///< in order of detection (by kind, then element)
  int num_errors = 0;
  int num_warnings = 0;

  int num_vertices = 0;        ///< vertices used by the faces counted
  int num_faces = 0;           ///< faces counted
  int num_edges = 0;           ///< undirected edges of those faces
  int num_components = 0;      ///< connected components (faces linked through edges)
  int num_boundary_loops = -1;
  int euler_characteristic = 0;  ///< V - E + F
  int genus = -1;              ///< total genus, from chi = 2c - 2g - b
  bool manifold = false;       ///< edge- and vertex-manifold and consistently oriented
  bool is_disk = false;        ///< no errors, one component, one boundary loop, genus 0

  /// True when there are no errors (warnings allowed).
  bool ok() const { return num_errors == 0; }
  /// Number of issues of one kind.
  int count(SurfaceIssueKind kind) const;
  /// One line: topology summary and counts per kind.
  std::string summary() const;
};

/// Checks a triangle mesh without changing it. Never throws for any mesh
/// content (only std::bad_alloc).
SurfaceReport validate_surface(const TriMesh& mesh, const SurfaceCheckOptions& options = {});

/// Throws unless `mesh` is a valid, consistently oriented disk (one
/// component, one boundary loop, genus 0). `what` names the mesh in the
/// message (e.g. a file name); `cut_hint`, when not empty, is offered as
/// the alternative to cutting by hand (e.g. "pass --cut FILE.obj" from a
/// command that has that option; the library names no option itself).
/// \throw TopologyError with the first errors of validate_surface(), or with
///        what the topology is and how to cut it into a disk.
void require_disk(const TriMesh& mesh, std::string_view what, std::string_view cut_hint = {});

/// Throws unless `mesh` has no errors in validate_surface() (any topology).
/// \throw TopologyError (or InvalidInput for non-finite coordinates) listing
///        the first errors.
void require_valid_surface(const TriMesh& mesh, std::string_view what);

}  // namespace knitforge
