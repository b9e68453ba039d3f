#include "knitforge/body/body_json.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

nlohmann::json measurements_to_json(const BodyMeasurements& m) {
  nlohmann::json j = nlohmann::json::object();
  for (int k = 0; k < kNumMeasurements; ++k)
    j[measurement_info(static_cast<Measurement>(k)).key] = std::round(m[static_cast<size_t>(k)] * 100.0) / 100.0;
  return j;
}

nlohmann::json body_params_to_json(const BodyModel& model, const BodyParams& params, const BodyMeasurements* measurements) {
  validate_body_params(model, params);
  nlohmann::json j;
  j["model"] = model.name;
  nlohmann::json shape = nlohmann::json::object();
  for (int k = 0; k < model.num_shapes(); ++k) shape[model.shape_names[static_cast<size_t>(k)]] = params.shape(k);
  j["shape"] = shape;
  nlohmann::json rot = nlohmann::json::object();
  for (int q = 0; q < model.num_joints(); ++q) {
    const Vec3& r = params.joint_rotations[static_cast<size_t>(q)];
    rot[model.joint_names[static_cast<size_t>(q)]] = {r.x(), r.y(), r.z()};
  }
  j["rotations_rad"] = rot;
  j["translation_mm"] = {params.translation_mm.x(), params.translation_mm.y(), params.translation_mm.z()};
  if (measurements) j["measurements_mm"] = measurements_to_json(*measurements);
  return j;
}

namespace {

Vec3 vec3(const nlohmann::json& v, const std::string& what, const std::string& key) {
  if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
    throw InvalidInput(fmt::format("{}: '{}' must be three numbers [x, y, z]", what, key));
  const Vec3 r(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  if (!r.allFinite()) throw InvalidInput(fmt::format("{}: '{}' is not finite", what, key));
  return r;
}

}  // namespace

BodyParams body_params_from_json(const BodyModel& model, const nlohmann::json& j, const std::string& what) {
  if (!j.is_object()) throw InvalidInput(fmt::format("{}: body parameters must be a JSON object", what));
  BodyParams p = zero_params(model);
  for (const auto& [key, value] : j.items()) {
    if (key == "model") {
      if (!value.is_string() || value.get<std::string>() != model.name)
        throw InvalidInput(fmt::format("{}: the parameters are for the model '{}', not '{}'", what,
                                       value.is_string() ? value.get<std::string>() : value.dump(), model.name));
    } else if (key == "shape") {
      if (!value.is_object()) throw InvalidInput(fmt::format("{}: 'shape' must be an object of name: value", what));
      for (const auto& [name, v] : value.items()) {
        const auto it = std::find(model.shape_names.begin(), model.shape_names.end(), name);
        if (it == model.shape_names.end())
          throw InvalidInput(fmt::format("{}: unknown shape parameter '{}' of model '{}'", what, name, model.name));
        if (!v.is_number()) throw InvalidInput(fmt::format("{}: shape '{}' must be a number", what, name));
        p.shape(it - model.shape_names.begin()) = v.get<double>();
      }
    } else if (key == "rotations_rad" || key == "rotations_deg") {
      if (!value.is_object()) throw InvalidInput(fmt::format("{}: '{}' must be an object of joint: [x, y, z]", what, key));
      const double scale = key == "rotations_deg" ? std::numbers::pi / 180.0 : 1.0;
      for (const auto& [name, v] : value.items()) {
        const int q = model.joint_index(name);
        if (q < 0) throw InvalidInput(fmt::format("{}: unknown joint '{}' of model '{}'", what, name, model.name));
        p.joint_rotations[static_cast<size_t>(q)] = scale * vec3(v, what, name);
      }
    } else if (key == "translation_mm") {
      p.translation_mm = vec3(value, what, key);
    } else if (key == "measurements_mm" || key == "joints_mm" || key == "targets_mm" ||
               key == "max_measurement_error_mm" || key == "newton_iterations" || key == "vertex_parts" ||
               key == "fit") {
      // Written by body make --params and body fit for people; not inputs,
      // so that those files can be read back as a starting pose and shape.
    } else {
      throw InvalidInput(fmt::format("{}: unknown key '{}' (expected model, shape, rotations_rad or rotations_deg, "
                                     "translation_mm)",
                                     what, key));
    }
  }
  validate_body_params(model, p);
  return p;
}

}  // namespace knitforge
