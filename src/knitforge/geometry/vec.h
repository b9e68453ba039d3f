#pragma once
/// \file vec.h
/// The small fixed-size vector types used throughout knitforge (Eigen).
/// All lengths are millimetres unless a name says otherwise.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace knitforge {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;

}  // namespace knitforge
