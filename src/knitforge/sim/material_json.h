#pragma once
/// \file material_json.h
/// Knit materials as user-editable JSON (docs/sim.md), every field named
/// with its unit:
///
///   {"name": "single-jersey",
///    "course_tension": {"segments": [[0, 60], [0.3, 1500]], "compression_n_per_m": 60},
///    "wale_tension":   {"segments": [[0, 150], [0.15, 2500]], "compression_n_per_m": 150},
///    "shear":          {"segments": [[0, 20], [0.5, 200]]},
///    "poisson_course_wale": 0.3, "bending_course_un_m": 1.0, "bending_wale_un_m": 2.0,
///    "areal_density_g_m2": 170, "thickness_mm": 0.6, "damping_per_s": 0.5,
///    "source": "..."}
///
/// A segment is [strain from which it applies, slope in N/m per unit
/// strain] (knit_material.h). Missing fields keep the default
/// (default_single_jersey()); unknown fields are an error (a typo would
/// silently keep a default).

#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/sim/knit_material.h"

namespace knitforge {

nlohmann::json material_to_json(const KnitMaterial& m);

/// \throw InvalidInput naming `where` (e.g. the file) and the field for an
///        unknown field, a wrong type or a value validate_material() refuses.
KnitMaterial material_from_json(const nlohmann::json& j, const std::string& where);

/// The JSON value of a file; `what` names the file's role in messages
/// ("material file"). \throw IOError when it cannot be opened or parsed
///        (naming the file and the parser's position).
nlohmann::json read_json_file(const std::string& path, const std::string& what);

/// Reads a material file. \throw IOError when it cannot be read or parsed
///        (naming the file and the parser's position); InvalidInput as above.
KnitMaterial read_material_json(const std::string& path);

}  // namespace knitforge
