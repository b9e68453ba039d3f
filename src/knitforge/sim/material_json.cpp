#include "knitforge/sim/material_json.h"

#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

nlohmann::json curve_json(const TensionCurve& c, bool shear) {
  nlohmann::json segs = nlohmann::json::array();
  for (const auto& [start, slope] : c.segments) segs.push_back({start, slope});
  nlohmann::json j = {{"segments", segs}};
  if (!shear) j["compression_n_per_m"] = c.compression_n_per_m;
  return j;
}

double number(const nlohmann::json& j, const std::string& where, const std::string& field) {
  if (!j.is_number()) throw InvalidInput(fmt::format("{}: '{}' must be a number (got {})", where, field, j.dump()));
  return j.get<double>();
}

TensionCurve curve_from(const nlohmann::json& j, const TensionCurve& def, const std::string& where,
                        const std::string& field, bool shear) {
  if (!j.is_object()) throw InvalidInput(fmt::format("{}: '{}' must be an object with \"segments\"", where, field));
  TensionCurve c = def;
  for (const auto& [key, value] : j.items()) {
    if (key == "segments") {
      if (!value.is_array() || value.empty()) {
        throw InvalidInput(fmt::format("{}: '{}.segments' must be a non-empty array of [strain, slope N/m]", where, field));
      }
      c.segments.clear();
      for (size_t k = 0; k < value.size(); ++k) {
        const auto& s = value[k];
        const std::string f = fmt::format("{}.segments[{}]", field, k);
        if (!s.is_array() || s.size() != 2) throw InvalidInput(fmt::format("{}: '{}' must be [strain, slope N/m]", where, f));
        c.segments.emplace_back(number(s[0], where, f), number(s[1], where, f));
      }
    } else if (key == "compression_n_per_m" && !shear) {
      c.compression_n_per_m = number(value, where, field + "." + key);
    } else {
      throw InvalidInput(fmt::format("{}: unknown field '{}.{}'", where, field, key));
    }
  }
  return c;
}

}  // namespace

nlohmann::json material_to_json(const KnitMaterial& m) {
  return {{"name", m.name},
          {"course_tension", curve_json(m.course, false)},
          {"wale_tension", curve_json(m.wale, false)},
          {"shear", curve_json(m.shear, true)},
          {"poisson_course_wale", m.poisson_course_wale},
          {"bending_course_un_m", m.bending_course_un_m},
          {"bending_wale_un_m", m.bending_wale_un_m},
          {"areal_density_g_m2", m.areal_density_g_m2},
          {"thickness_mm", m.thickness_mm},
          {"damping_per_s", m.damping_per_s},
          {"source", m.source}};
}

KnitMaterial material_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InvalidInput(fmt::format("{}: a material must be a JSON object", where));
  KnitMaterial m = default_single_jersey();
  m.source = "user material (" + where + ")";
  for (const auto& [key, value] : j.items()) {
    if (key == "name" || key == "source") {
      if (!value.is_string()) throw InvalidInput(fmt::format("{}: '{}' must be a string", where, key));
      (key == "name" ? m.name : m.source) = value.get<std::string>();
    } else if (key == "course_tension") {
      m.course = curve_from(value, m.course, where, key, false);
    } else if (key == "wale_tension") {
      m.wale = curve_from(value, m.wale, where, key, false);
    } else if (key == "shear") {
      m.shear = curve_from(value, m.shear, where, key, true);
    } else if (key == "poisson_course_wale") {
      m.poisson_course_wale = number(value, where, key);
    } else if (key == "bending_course_un_m") {
      m.bending_course_un_m = number(value, where, key);
    } else if (key == "bending_wale_un_m") {
      m.bending_wale_un_m = number(value, where, key);
    } else if (key == "areal_density_g_m2") {
      m.areal_density_g_m2 = number(value, where, key);
    } else if (key == "thickness_mm") {
      m.thickness_mm = number(value, where, key);
    } else if (key == "damping_per_s") {
      m.damping_per_s = number(value, where, key);
    } else {
      throw InvalidInput(fmt::format("{}: unknown material field '{}' (fields: name, course_tension, wale_tension, "
                                     "shear, poisson_course_wale, bending_course_un_m, bending_wale_un_m, "
                                     "areal_density_g_m2, thickness_mm, damping_per_s, source)",
                                     where, key));
    }
  }
  try {
    validate_material(m);
  } catch (const InvalidInput& e) {
    throw InvalidInput(fmt::format("{}: {}", where, e.what()));
  }
  return m;
}

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw IOError(fmt::format("{}: cannot open the {}", path, what));
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    return nlohmann::json::parse(ss.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw IOError(fmt::format("{}: not valid JSON ({})", path, e.what()));
  }
}

KnitMaterial read_material_json(const std::string& path) {
  return material_from_json(read_json_file(path, "material file"), path);
}

}  // namespace knitforge
