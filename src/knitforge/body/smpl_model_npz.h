#pragma once
/// \file smpl_model_npz.h
/// Loads an SMPL-format body model (SMPL, SMPL+H, SMPL-X: Loper et al. 2015
/// and successors) from the `.npz` file a licensed user supplies into a
/// BodyModel. knitforge never ships such a file: the models are licensed
/// for non-commercial use only (https://smpl.is.tue.mpg.de).
///
/// The arrays read (names as in the official npz files; V vertices, F
/// faces, K shape directions, J joints):
///
/// | key | shape | meaning |
/// |---|---|---|
/// | `v_template`   | V x 3             | rest vertices, metres, y up, facing +z |
/// | `f`            | F x 3 (integers)  | triangles |
/// | `shapedirs`    | V x 3 x K         | shape blend shapes (metres per unit beta) |
/// | `posedirs`     | V x 3 x 9(J-1)    | pose-corrective blend shapes (optional) |
/// | `J_regressor`  | J x V (dense)     | rest joints from the shaped vertices |
/// | `kintree_table`| 2 x J (integers)  | row 0: parent of each joint (the root's a
///                                        sentinel such as 4294967295 or -1), row 1: 0..J-1 |
/// | `weights`      | V x J             | skinning weights (rows sum to 1) |
///
/// Other arrays in the file (strings, `J`, `hands_components`, ...) are not
/// read. Conversions into body_model.h's conventions: metres -> millimetres,
/// and the rotation C = [[1,0,0],[0,0,-1],[0,1,0]] (a quarter turn about x):
/// SMPL's up (+y) becomes +z, its front (+z) becomes -y, its left side (+x)
/// stays +x. Vertices, joints and shape directions are mapped by 1000 C; a
/// local rotation R in SMPL's frame is C R C^T in ours, so the pose feature
/// vec(R - I) of SMPL is (C^T (x) C^T) times ours per joint and the pose
/// basis is mapped by both sides. Axis-angle poses written for SMPL convert
/// as w_ours = C w_smpl.
///
/// Joint names: SMPL's 24 ("pelvis", "left_hip", ..., "right_hand") when J
/// = 24, so the named poses (body_pose.h) apply; for J = 52 (SMPL+H) and 55
/// (SMPL-X), whose first 22 joints are SMPL's body joints in SMPL's order
/// (the hands' and face's joints follow), SMPL's names for those 22 and
/// "joint_22".. for the rest; "joint_0".. for any other J. Shape names
/// "beta0".. (unitless).
///
/// Part labels, smooth part fields and the measurement landmarks are then
/// derived from the model's own weights, joints and geometry
/// (label_smpl_body(), smpl_body_parts.h), so measurements
/// (body_measurements.h), garment regions (cut_body_region.h),
/// scan_vertex_parts() and the fitter's zero weight on head, hands and feet
/// work on it. A model they cannot be derived for (other joints, a
/// template that is not an upright T-pose) still loads, without labels and
/// landmarks, with the reason in BodyModel::labels_note; what needs them
/// then refuses it with that reason.

#include <string>

#include "knitforge/body/body_model.h"

namespace knitforge {

/// Options of load_smpl_model().
struct SmplLoadOptions {
  /// Keep only the first this many shape directions (0: all). SMPL files
  /// have 10 or 300; the cost of fitting grows with their number.
  int max_shapes = 0;
  /// Skinning weight rows may differ from 1 by this much (float32 files);
  /// they are then rescaled to sum to 1 exactly. Larger: refused.
  double weight_sum_tolerance = 1e-4;
  /// Derive part labels, part fields and landmarks (label_smpl_body()).
  bool derive_labels = true;
};

/// Reads `path` (an .npz file) into a BodyModel named after the file name,
/// converted as the file comment says, and validated (validate_body_model).
/// \throw IOError naming the file and the entry: the file cannot be read as
///        .npz (read_npz.h), a required array is missing, has the wrong
///        number of dimensions or sizes inconsistent with the others, an
///        integer array (`f`, `kintree_table`) holds floats or values out of
///        range, a parent does not precede its child, weights are negative
///        or do not sum to 1, a regressor row does not sum to 1, or a value
///        is not finite. \throw InvalidInput for options out of range.
BodyModel load_smpl_model(const std::string& path, const SmplLoadOptions& options = {});

/// SMPL's 24 joint names in its joint order.
const std::vector<std::string>& smpl_joint_names();

/// The rotation C from SMPL's axes to knitforge's (see the file comment).
Mat3 smpl_to_knitforge_axes();

}  // namespace knitforge
