#include "knitforge/design/flatten/dart_json.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& source, const std::string& where, const std::string& what) {
  throw InvalidInput(fmt::format("{}: {}: {}", source, where, what));
}

double number(const json& j, const std::string& source, const std::string& where) {
  if (!j.is_number()) fail(source, where, "must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(source, where, "must be finite");
  return v;
}

Vec3 triple(const json& j, const std::string& source, const std::string& where) {
  if (!j.is_array() || j.size() != 3) fail(source, where, "must be an array of 3 numbers");
  return Vec3(number(j[0], source, where + "[0]"), number(j[1], source, where + "[1]"),
              number(j[2], source, where + "[2]"));
}

DartWaypoint parse_point(const json& j, const std::string& source, const std::string& where, double scale) {
  if (!j.is_object())
    fail(source, where, "must be an object with \"vertex\", \"face\" + \"bary\", or \"position\"");
  for (const auto& [key, value] : j.items()) {
    (void)value;
    if (key != "vertex" && key != "face" && key != "bary" && key != "position") {
      fail(source, where, fmt::format("unknown key \"{}\" (use vertex, face + bary, or position)", key));
    }
  }
  const int kinds =
      (j.contains("vertex") ? 1 : 0) + (j.contains("face") ? 1 : 0) + (j.contains("position") ? 1 : 0);
  if (kinds != 1)
    fail(source, where, "give exactly one of \"vertex\", \"face\" (+ \"bary\") or \"position\"");
  if (j.contains("vertex")) {
    if (!j["vertex"].is_number_integer() || j["vertex"].get<long long>() < 0) {
      fail(source, where + ".vertex", "must be a vertex index >= 0");
    }
    return DartWaypoint::at_vertex(static_cast<int>(j["vertex"].get<long long>()));
  }
  if (j.contains("face")) {
    if (!j["face"].is_number_integer() || j["face"].get<long long>() < 0) {
      fail(source, where + ".face", "must be a face index >= 0");
    }
    if (!j.contains("bary")) fail(source, where, "\"face\" needs \"bary\": [b0, b1, b2]");
    return DartWaypoint::in_face(static_cast<int>(j["face"].get<long long>()),
                                 triple(j["bary"], source, where + ".bary"));
  }
  if (j.contains("bary")) fail(source, where, "\"bary\" is only used with \"face\"");
  return DartWaypoint::at_position(scale * triple(j["position"], source, where + ".position"));
}

}  // namespace

std::vector<DartSpec> parse_darts_json(std::string_view text, const std::string& source,
                                       double position_scale) {
  json root;
  // The last key read, to say where a number out of range or a syntax error is
  // (the parser's own messages quote raw input and its exception names).
  std::string last_key;
  const json::parser_callback_t remember_key = [&last_key](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::key && parsed.is_string()) {
      last_key.clear();
      for (unsigned char c : parsed.get_ref<const std::string&>()) {
        if (last_key.size() >= 40) break;
        last_key += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
      }
    }
    return true;
  };
  auto after_key = [&last_key] { return last_key.empty() ? std::string() : fmt::format(" (after key \"{}\")", last_key); };
  try {
    root = json::parse(text.begin(), text.end(), remember_key);
  } catch (const json::parse_error& e) {
    throw InvalidInput(fmt::format("{}: byte {}: not valid JSON{}; check the syntax there", source, e.byte, after_key()));
  } catch (const json::out_of_range&) {
    throw InvalidInput(fmt::format("{}: a number is out of range{}; use a finite number", source, after_key()));
  } catch (const json::exception&) {
    throw InvalidInput(fmt::format("{}: not valid JSON{}", source, after_key()));
  }
  const json* list = &root;
  if (root.is_object()) {
    for (const auto& [key, value] : root.items()) {
      (void)value;
      if (key != "darts")
        fail(source, "top level", fmt::format("unknown key \"{}\" (expected \"darts\")", key));
    }
    if (!root.contains("darts")) fail(source, "top level", "missing \"darts\": [...]");
    list = &root["darts"];
  }
  if (!list->is_array()) fail(source, "\"darts\"", "must be an array of darts");
  std::vector<DartSpec> out;
  for (size_t i = 0; i < list->size(); ++i) {
    const json& d = (*list)[i];
    const std::string where = fmt::format("dart {}", i);
    if (!d.is_object()) fail(source, where, "must be an object");
    DartSpec spec;
    for (const auto& [key, value] : d.items()) {
      if (key == "type") {
        if (!value.is_string()) fail(source, where + ".type", "must be \"one-end\" or \"two-end\"");
        const std::string t = value.get<std::string>();
        if (t == "one-end") {
          spec.type = DartType::OneEnd;
        } else if (t == "two-end") {
          spec.type = DartType::TwoEnd;
        } else {
          fail(source, where + ".type", fmt::format("must be \"one-end\" or \"two-end\" (got \"{}\")", t));
        }
      } else if (key == "orientation") {
        if (!value.is_string())
          fail(source, where + ".orientation", "must be \"horizontal\" or \"vertical\"");
        const std::string o = value.get<std::string>();
        if (o == "horizontal") {
          spec.orientation = DartOrientation::Horizontal;
        } else if (o == "vertical") {
          spec.orientation = DartOrientation::Vertical;
        } else {
          fail(source, where + ".orientation",
               fmt::format("must be \"horizontal\" or \"vertical\" (got \"{}\")", o));
        }
      } else if (key == "to_boundary") {
        if (!value.is_boolean()) fail(source, where + ".to_boundary", "must be true or false");
        spec.to_boundary = value.get<bool>();
      } else if (key == "points") {
        if (!value.is_array()) fail(source, where + ".points", "must be an array of points");
        for (size_t k = 0; k < value.size(); ++k) {
          spec.points.push_back(
              parse_point(value[k], source, fmt::format("{}.points[{}]", where, k), position_scale));
        }
      } else {
        fail(source, where,
             fmt::format("unknown key \"{}\" (expected type, orientation, to_boundary, points)", key));
      }
    }
    if (!d.contains("points")) fail(source, where, "missing \"points\"");
    out.push_back(std::move(spec));
  }
  return out;
}

std::string darts_to_json(const std::vector<DartSpec>& darts, double position_scale) {
  json list = json::array();
  for (const auto& d : darts) {
    json points = json::array();
    for (const auto& p : d.points) {
      if (p.vertex >= 0) {
        points.push_back({{"vertex", p.vertex}});
      } else if (p.face >= 0) {
        points.push_back({{"face", p.face}, {"bary", {p.bary.x(), p.bary.y(), p.bary.z()}}});
      } else {
        const Vec3 q = p.position / position_scale;
        points.push_back({{"position", {q.x(), q.y(), q.z()}}});
      }
    }
    list.push_back({{"type", std::string(to_string(d.type))},
                    {"orientation", std::string(to_string(d.orientation))},
                    {"to_boundary", d.to_boundary},
                    {"points", points}});
  }
  return json{{"darts", list}}.dump(2) + "\n";
}

}  // namespace knitforge
