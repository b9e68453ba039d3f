#pragma once
/// \file read_gltf_animation.h
/// Reads an animated triangle mesh from glTF 2.0 (`.glb`, or `.gltf` with
/// its buffers in data: URIs or files next to it): the moving body of
/// `knitforge cloth` (docs/formats.md, "Cloth scene", body "animation").
/// What write_animation_glb() (io/gltf.h) writes reads back exactly.
///
/// **What is read.** The triangles of every mesh node of the scene (the
/// file's "scene", else scene 0, else every root node), or only of the
/// nodes whose node or mesh name is `GltfReadOptions::mesh_name`, as one
/// mesh: primitives in mode TRIANGLES (4, the default), TRIANGLE_STRIP (5)
/// and TRIANGLE_FAN (6); POSITION float32 VEC3; indices unsigned
/// byte/short/int or none. Vertices of one primitive at the same position
/// with the same morph displacements and skin weights are merged (exporters
/// split vertices at UV and normal seams; the body's parts are its connected
/// components).
///
/// **Motion.** One animation (the only one, or the one named
/// `GltfReadOptions::animation`) with channels on
///   - `weights`: morph targets (POSITION displacements, float32 VEC3), the
///     vertex = base + Σ wₖ targetₖ (what our writer produces);
///   - `translation`, `rotation`, `scale` of any node: rigid (or scaled)
///     motion of the mesh nodes and their parents. Node `matrix` is read as a
///     static transform.
/// Interpolation STEP, LINEAR (rotations by spherical interpolation) and
/// CUBICSPLINE; before the first key the first value holds, after the last
/// the last. Sampler outputs float32, or normalised integers for rotations
/// and weights, as the specification allows. A file without an animation is
/// a static body.
///
/// **Skinning** (a mesh node with a "skin", what character exporters write):
/// linear blend skinning as the specification defines it, after the morph
/// targets: vertex = Σᵢ wᵢ Gᵢ Bᵢ x, over the vertex's joints i (JOINTS_n /
/// WEIGHTS_n, n = 0, 1, ..., four per set), Gᵢ the joint node's global
/// transform at the time (its animated TRS and its parents'), Bᵢ its inverse
/// bind matrix (skin.inverseBindMatrices, MAT4 float32; identity when
/// absent); the skinned node's own transform is ignored, as the
/// specification asks. Checked: every joint a node, JOINTS_n unsigned
/// byte/short, WEIGHTS_n float32 or normalised unsigned byte/short, no
/// negative weight, a used joint index inside the skin, each vertex's
/// weights summing to 1 within 0.02 (then rescaled to 1: 8-bit weights are
/// off by up to 0.008), inverse bind matrices' last row (0, 0, 0, 1).
///
/// **Refused, with what to do:** any "extensionsRequired" (Draco, meshopt,
/// quantization, ...), points and lines, animation channels on a "pointer"
/// or unknown path, several animations without a name chosen, external
/// buffers given by absolute path or a URL. JOINTS_n / WEIGHTS_n of a node
/// without a skin are ignored.
///
/// **Checked** before use: the GLB header and chunks (version, lengths,
/// the JSON chunk first), every index into buffers, bufferViews, accessors,
/// meshes, nodes, samplers; every accessor's component type, type and count
/// for its use; accessor and view ranges against their view and buffer
/// (byteOffset, byteStride, count); sparse accessors' indices; the node
/// hierarchy (no cycles, one parent); key times finite and strictly
/// increasing; every value finite; index values in range. Errors are
/// IOError naming the file and the element ("walk.glb: accessors[4]: ...").

#include <array>
#include <string>
#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

struct GltfReadOptions {
  /// "" = every mesh node of the scene; else the nodes whose name, or whose
  /// mesh's name, is this.
  std::string mesh_name;
  /// "" = the file's only animation (none: a static mesh); else its name,
  /// or "#N" for the N-th (0-based) animation.
  std::string animation;
};

/// An animated mesh as read (plain data; sample it with gltf_positions_at()).
struct GltfAnimatedMesh {
  std::string path;  ///< for messages
  std::vector<std::array<int, 3>> faces;
  int num_vertices = 0;
  std::string animation_name;  ///< "" when static
  double start_s = 0.0, end_s = 0.0;  ///< the animation's first and last key times

  // --- what the sampling needs ---
  struct Node {
    int parent = -1;
    bool has_matrix = false;
    std::array<double, 16> matrix{};  ///< column-major, as in the file
    Vec3 translation = Vec3::Zero();
    std::array<double, 4> rotation{0, 0, 0, 1};  ///< x, y, z, w
    Vec3 scale = Vec3::Ones();
    std::vector<double> weights;  ///< the node's (or its mesh's) default morph weights
  };
  /// A skin: the node of each joint and its inverse bind matrix.
  struct Skin {
    std::vector<int> joints;
    std::vector<std::array<double, 16>> inverse_bind;  ///< per joint, column-major
  };
  /// One primitive of one mesh node: vertices [first_vertex, first_vertex + base.size()).
  struct Part {
    int node = 0;
    int skin = -1;  ///< index into skins; -1: moved by the node's transform
    int first_vertex = 0;
    std::vector<Vec3> base;
    std::vector<std::vector<Vec3>> targets;  ///< per morph target, per vertex
    /// Skinned parts: vertex v's joints (indices into the skin's joints) and
    /// weights (summing to 1) are entries [influence_start[v],
    /// influence_start[v + 1]) of influence_joint and influence_weight.
    std::vector<int> influence_start, influence_joint;
    std::vector<double> influence_weight;
  };
  enum class Path { Translation, Rotation, Scale, Weights };
  enum class Interpolation { Step, Linear, CubicSpline };
  struct Channel {
    int node = 0;
    Path path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<double> times;
    /// Per key `width` values (3 for T/S, 4 for R, the node's weights'
    /// count); CUBICSPLINE: per key in-tangent, value, out-tangent.
    std::vector<double> values;
    int width = 0;
  };
  std::vector<Node> nodes;
  std::vector<Skin> skins;
  std::vector<Part> parts;
  std::vector<Channel> channels;
};

/// Reads `path` (.glb or .gltf, by content: a GLB starts with "glTF").
/// \throw IOError when it cannot be read or is malformed (naming the file
///        and the element, see the file comment); InvalidInput when
///        `options` names no mesh or animation of the file (listing those
///        there are) or the chosen nodes have no triangle.
GltfAnimatedMesh read_gltf_animation(const std::string& path, const GltfReadOptions& options = {});

/// The vertex positions at time `t_s` (seconds, the file's clock; clamped
/// to [start_s, end_s] by the samplers), in the file's units.
/// \throw InvalidInput when a position is not finite (transforms that
///        overflow).
std::vector<Vec3> gltf_positions_at(const GltfAnimatedMesh& mesh, double t_s);

}  // namespace knitforge
