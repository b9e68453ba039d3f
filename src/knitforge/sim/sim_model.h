#pragma once
/// \file sim_model.h
/// The immutable simulation model of a piece of fabric (docs/sim.md): rest
/// data computed once from the design, shared by every energy term.
///
///  - triangles: each Knit stitch (quad) split into two along its shorter
///    designed diagonal (ties alternate in a checkerboard of course + wale),
///    each shaping stitch one triangle;
///  - per triangle a MembraneElement: the inverse of its rest-shape matrix
///    in the stitch's course/wale frame (x along the course, y along the
///    wale), its rest area and its material;
///  - per interior edge a BendingHinge: the two opposite vertices, the rest
///    geometry of the flat hinge and its stiffness;
///  - the lumped mass of every vertex (a third of each incident triangle's
///    rest area times the areal density) and its air damping.
///
/// Rest state from the design: every stitch at its ideal size (sw x sh, the
/// stitch types' own shapes of ideal_stitch_shape()), so neighbouring
/// stitches of different types need not fit together; the equilibrium is
/// where their disagreement balances.

#include <array>
#include <string>
#include <vector>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/geometry/vec.h"
#include "knitforge/sim/knit_material.h"

namespace knitforge {

/// One membrane triangle.
struct MembraneElement {
  std::array<int, 3> v{};  ///< vertex indices (counter-clockwise)
  /// Inverse of [P1 - P0, P2 - P0], the rest corners P_i in the material
  /// frame (mm): F = [x1 - x0, x2 - x0] rest_inverse maps rest to deformed
  /// line elements; F's first column is the deformed course direction per
  /// unit rest length, the second the wale direction.
  Mat2 rest_inverse = Mat2::Identity();
  double rest_area_mm2 = 0.0;
  int material = 0;  ///< index into SimModel::materials
  int stitch = -1;   ///< stitch it belongs to (-1 for a triangle-mesh model)
};

/// A hinge: two triangles sharing edge (v[0], v[1]); v[2] is the third
/// vertex of the triangle with the edge as (v0, v1), v[3] of the other.
/// Bending energy k θ² (bending_energy.h); the rest shape is flat.
struct BendingHinge {
  std::array<int, 4> v{};
  double stiffness = 0.0;  ///< k (µJ): ½ D_e |e|² / (A_0 + A_1) of the rest hinge
  /// The two elements it joins: [0] the one holding v[2], [1] the one
  /// holding v[3] (-1 when not known).
  std::array<int, 2> elements{-1, -1};
};

/// The hinge on the diagonal inside a split Knit stitch is this many times
/// stiffer than the discrete-shell weight: a knit loop bends with its
/// neighbours, it does not crease along its own diagonal, and with the plain
/// weight the diagonal folds make a strip about 20 % softer than its
/// rigidity D (a cantilever's tip sags 1.33 x q L⁴/8D on a 1 mm mesh, 1.27 x
/// on 0.5 mm, not converging); with 10 x it sags 1.13 x and 1.07 x,
/// converging to beam theory at first order like a discrete beam
/// (tests/sim/equilibrium_test.cpp, docs/sim.md).
inline constexpr double kStitchDiagonalStiffening = 10.0;

/// The model. Positions are mm, masses kg.
struct SimModel {
  std::vector<Vec3> rest_positions;  ///< the designed geometry (start of a simulation)
  std::vector<MembraneElement> elements;
  std::vector<BendingHinge> hinges;
  std::vector<double> vertex_mass_kg;
  /// Air damping per vertex: the sum of α m over its share of each incident
  /// element (kg/s; the damping force is -vertex_damping v).
  std::vector<double> vertex_damping_kg_s;
  /// A third of the rest area of every incident element (mm²).
  std::vector<double> vertex_area_mm2;
  std::vector<KnitMaterial> materials;
  /// Vertices held in place (pins), sorted; the simulation keeps them at
  /// their current (or prescribed) positions.
  std::vector<int> pinned;

  int num_vertices() const { return static_cast<int>(rest_positions.size()); }
  int num_elements() const { return static_cast<int>(elements.size()); }
  /// The element faces as a triangle mesh (positions = rest_positions).
  TriMesh triangles() const;
};

/// Options of build_sim_model().
struct SimModelOptions {
  /// Material of every element (build_sim_model(StitchMesh) uses materials[0]
  /// unless a stitch's yarn selects another: yarn y -> materials[y] when
  /// there are more than y materials).
  std::vector<KnitMaterial> materials{default_single_jersey()};
};

/// Model of a stitch mesh whose rest state is every stitch at its ideal
/// shape (ideal_stitch_shape() for `params`), with the designed geometry as
/// the initial positions.
/// \throw InvalidInput for an empty mesh, non-finite positions, bad params
///        or materials (validate_material()); TopologyError for a vertex
///        index out of range, a repeated corner or an edge shared by more
///        than two triangles (naming the stitch).
SimModel build_sim_model(const StitchMesh& mesh, const KnitParams& params, const SimModelOptions& options = {});

/// Model of a triangle mesh (a garment) at rest as given, with the course
/// direction of each face: `course_directions` holds one vector per face
/// (projected onto the face's plane; the wale direction is n x course), or
/// one vector for all faces; `face_materials` empty (all materials[0]) or
/// one index per face.
/// \throw InvalidInput for an empty mesh, degenerate faces, a course
///        direction (nearly) normal to its face, bad indices or materials;
///        TopologyError for a non-manifold edge (naming the faces).
SimModel build_sim_model(const TriMesh& mesh, const std::vector<Vec3>& course_directions,
                         const std::vector<int>& face_materials = {}, const SimModelOptions& options = {});

}  // namespace knitforge
