#include "knitforge/body/json_values.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge::json_values {

double number(const nlohmann::json& j, const std::string& where) {
  if (!j.is_number()) throw InvalidInput(fmt::format("{}: expected a number, found {}", where, j.dump()));
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw InvalidInput(fmt::format("{}: not a finite number", where));
  return v;
}

int integer(const nlohmann::json& j, const std::string& where, int lo, int hi) {
  const double v = number(j, where);
  if (v != std::floor(v) || v < lo || v > hi)
    throw InvalidInput(fmt::format("{}: expected a whole number in {}..{}, found {}", where, lo, hi, j.dump()));
  return static_cast<int>(v);
}

Eigen::VectorXd numbers(const nlohmann::json& j, const std::string& where, int n) {
  if (!j.is_array() || static_cast<int>(j.size()) != n)
    throw InvalidInput(fmt::format("{}: expected {} numbers, found {}", where, n, j.dump()));
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = number(j[static_cast<size_t>(i)], where);
  return v;
}

Vec2 vec2(const nlohmann::json& j, const std::string& where) { return numbers(j, where, 2); }
Vec3 vec3(const nlohmann::json& j, const std::string& where) { return numbers(j, where, 3); }

Mat3 mat3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3)
    throw InvalidInput(fmt::format("{}: expected a 3 x 3 matrix as three rows of three numbers", where));
  Mat3 m;
  for (int r = 0; r < 3; ++r) m.row(r) = vec3(j[static_cast<size_t>(r)], fmt::format("{} row {}", where, r)).transpose();
  return m;
}

Mat3 rotation(const nlohmann::json& j, const std::string& where) {
  const Mat3 R = mat3(j, where);
  if (!((R * R.transpose() - Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-6) || !(R.determinant() > 0.0))
    throw InvalidInput(fmt::format("{} is not a rotation (orthonormal with determinant +1)", where));
  return R;
}

const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw InvalidInput(fmt::format("{}: missing \"{}\"", where, key));
  return j.at(key);
}

nlohmann::json to_json(const Mat3& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) rows.push_back({m(r, 0), m(r, 1), m(r, 2)});
  return rows;
}

nlohmann::json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace knitforge::json_values
