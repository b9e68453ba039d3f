#pragma once
/// \file axis_angle.h
/// Rotations as axis-angle vectors (direction = axis, length = angle in
/// radians; SMPL's pose parameters) and as matrices, with the exponential
/// map used for the local increments of the fitter.

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// [a]x: the matrix with [a]x b = a x b.
Mat3 skew(const Vec3& a);

/// exp([w]x): Rodrigues' formula (exact; a Taylor series for tiny angles).
Mat3 rotation_from_axis_angle(const Vec3& w);

/// The axis-angle vector of a rotation matrix, angle in [0, pi]; robust at 0
/// and near pi. \pre R is a rotation (orthonormal, det +1).
Vec3 axis_angle_from_rotation(const Mat3& R);

/// The rotation closest to M in the Frobenius norm (SVD; det +1).
Mat3 nearest_rotation(const Mat3& M);

/// Angle of a rotation matrix (radians, in [0, pi]).
double rotation_angle(const Mat3& R);

}  // namespace knitforge
