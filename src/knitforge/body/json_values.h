#pragma once
/// \file json_values.h
/// Reading checked values out of the body module's JSON files (keypoint
/// views, depth cameras, calibrations): each function names `where` (the
/// file and the key) in its message when the value is missing, of the wrong
/// type or not finite.

#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/geometry/vec.h"

namespace knitforge::json_values {

/// A finite number. \throw InvalidInput "<where>: expected a number, found ...".
double number(const nlohmann::json& j, const std::string& where);

/// A whole number in [lo, hi]. \throw InvalidInput naming `where` and the range.
int integer(const nlohmann::json& j, const std::string& where, int lo, int hi);

/// N finite numbers. \throw InvalidInput naming `where`.
Eigen::VectorXd numbers(const nlohmann::json& j, const std::string& where, int n);
Vec2 vec2(const nlohmann::json& j, const std::string& where);
Vec3 vec3(const nlohmann::json& j, const std::string& where);

/// A 3 x 3 matrix given as three rows of three numbers.
Mat3 mat3(const nlohmann::json& j, const std::string& where);

/// A rotation matrix: mat3() that is orthonormal to 1e-6 with determinant +1
/// ("<where> is not a rotation ..." otherwise: give where as "file: R").
Mat3 rotation(const nlohmann::json& j, const std::string& where);

/// j[key]. \throw InvalidInput "<where>: missing \"key\"" (also when j is not an object).
const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& where);

/// JSON rows of a 3 x 3 matrix and an array of a 3-vector (for writing).
nlohmann::json to_json(const Mat3& m);
nlohmann::json to_json(const Vec3& v);

}  // namespace knitforge::json_values
