#pragma once
/// \file transfer_garment.h
/// Style transfer (seed §5.5.1, eq. 5.13): a garment designed on one body
/// moved to another body of the same model (the same topology: vertex i of
/// one is vertex i of the other). What `knitforge body transfer` does.
///
/// Rigging, on body A: each garment vertex v is written in the local frame
/// of a face f = (f0, f1, f2) of A,
///     v = f0 + w1 (f1 - f0) + w2 (f2 - f0) + w3 n,          (eq. 5.13)
/// n the face's unit normal (so w3 is the signed offset in mm, and a
/// garment keeps its ease on a body of another size); the three
/// coefficients are unique for a non-degenerate face. As the seed does in
/// practice, v is rigged to several faces, the 1-ring of its closest body
/// vertex (the corner nearest to v of the face holding v's closest point
/// on A), and on body B it is the mean over those faces of the same
/// combination of B's face frames. This is smoother than one face: the
/// garment follows a blend of the neighbouring frames instead of jumping
/// between faces.
///
/// Properties (tested): B = A gives the garment back (to round-off); a
/// rigid motion of the body moves the garment by the same motion (each
/// face frame moves rigidly); a garment offset by d along the body's
/// normals stays at about d from B.
///
/// Faces of A with zero area cannot hold a frame; they are left out of the
/// rings (a vertex whose ring has none throws).

#include <vector>

#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// One garment vertex's rig: the faces and their coefficients (w1, w2, w3).
struct GarmentVertexRig {
  std::vector<int> faces;
  std::vector<Vec3> weights;
  int body_vertex = -1;  ///< the closest body vertex whose ring it is
};

/// The rig of every garment vertex.
struct GarmentRig {
  int body_vertices = 0;  ///< vertex count of the body it was made on
  int body_faces = 0;
  std::vector<GarmentVertexRig> vertices;
};

/// Rigs `garment_vertices` to `body_a` (eq. 5.13 on the 1-ring faces).
/// \throw InvalidInput when the body has no faces, a point is not finite,
///        or a vertex's ring has only degenerate faces.
GarmentRig rig_garment(const TriMesh& body_a, const std::vector<Vec3>& garment_vertices);

/// The rigged vertices on `body_b` (same topology as the rig's body).
/// \throw InvalidInput when body_b's vertex or face count differs from the
///        rig's body.
std::vector<Vec3> deform_rigged_garment(const GarmentRig& rig, const TriMesh& body_b);

/// The garment moved from body A to body B: rig_garment() then
/// deform_rigged_garment(); the garment's faces are kept.
/// \throw InvalidInput when A and B do not have the same faces, or as above.
TriMesh transfer_garment(const TriMesh& garment, const TriMesh& body_a, const TriMesh& body_b);

}  // namespace knitforge
