#pragma once
/// \file skin_body.h
/// Forward kinematics and linear blend skinning (SMPL's second step), and
/// pose_body(), the whole model Θ -> mesh. Pure functions: no caches, no
/// "update first".
///
/// With rest joints J (from shape_body()) and local rotations R_j:
///   global rotation  Q_0 = R_0,            Q_j = Q_p R_j
///   joint position   o_0 = J_0 + t,        o_j = o_p + Q_p (J_j - J_p)
///   vertex           v_i = sum_j w_ij (Q_j (u_i - J_j) + o_j)
/// where p = parents[j], t the translation and u_i the shaped vertex plus
/// the pose-corrective blend shapes (pose_basis * vec(R_j - I), when the
/// model has them). Zero rotations reproduce the shaped rest body moved by t.

#include <vector>

#include "knitforge/body/body_model.h"
#include "knitforge/body/shape_body.h"

namespace knitforge {

/// A posed body.
struct PosedBody {
  std::vector<Vec3> vertices;         ///< V posed vertices (mm)
  std::vector<Vec3> joints;           ///< J posed joint positions o_j (mm)
  std::vector<Mat3> joint_rotations;  ///< J global rotations Q_j
  std::vector<Mat3> local_rotations;  ///< J local rotations R_j
  std::vector<Vec3> rest_vertices;    ///< V shaped vertices u_i before skinning (with pose correctives)
  std::vector<Vec3> rest_joints;      ///< J rest joints J_j of the shape
};

/// Poses a shaped body. `rotations`: J axis-angle vectors (rad).
/// \throw InvalidInput on size mismatches or non-finite values.
PosedBody skin_body(const BodyModel& model, const ShapedBody& shaped, const std::vector<Vec3>& rotations,
                    const Vec3& translation_mm);

/// shape_body() then skin_body(). \throw InvalidInput as validate_body_params().
PosedBody pose_body(const BodyModel& model, const BodyParams& params);

/// The posed body as a mesh (the model's faces).
TriMesh posed_mesh(const BodyModel& model, const PosedBody& posed);

}  // namespace knitforge
