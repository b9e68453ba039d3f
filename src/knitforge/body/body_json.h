#pragma once
/// \file body_json.h
/// Body parameters and measurements as JSON (what `knitforge body make`
/// and `body fit` write and `body transfer`, `body make --pose` read):
///
///   { "model": "knitforge-body",
///     "shape": { "stature": 12.5, "chest_girth": -30.0, ... },
///     "rotations_rad": { "left_shoulder": [0, 0.785, 0], ... },
///     "translation_mm": [0, 0, 0],
///     "measurements_mm": { "stature": 1772.5, ... } }
///
/// Shape values are in the model's units (mm of the measurement for the
/// generated model). Rotations are axis-angle vectors per joint name;
/// "rotations_deg" is accepted instead, in degrees. Joints and shape values
/// not given are zero. "measurements_mm" is written for people and ignored
/// on reading, as are the other keys that `body make --params` and `body
/// fit` add ("joints_mm", "targets_mm", "max_measurement_error_mm",
/// "newton_iterations", "vertex_parts", "fit"): their files read back as
/// parameters.

#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/body/body_measurements.h"
#include "knitforge/body/body_model.h"

namespace knitforge {

/// The JSON of `params` (and, when given, of the measurements).
nlohmann::json body_params_to_json(const BodyModel& model, const BodyParams& params,
                                   const BodyMeasurements* measurements = nullptr);

/// Parameters from JSON. `what` names the source (a file) in messages.
/// \throw InvalidInput naming `what` and the key when a key is unknown
///        (shape name, joint name), a value is not a number or not three
///        numbers, or the model name differs from `model.name`.
BodyParams body_params_from_json(const BodyModel& model, const nlohmann::json& json, const std::string& what);

/// {"stature": 1760.0, ...} by measurement key.
nlohmann::json measurements_to_json(const BodyMeasurements& m);

}  // namespace knitforge
