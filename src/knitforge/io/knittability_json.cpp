#include "knitforge/io/knittability_json.h"

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

nlohmann::json to_json(const KnittabilityReport& report) {
  nlohmann::json j;
  j["knittable"] = report.ok();
  j["errors"] = report.num_errors();
  j["warnings"] = report.num_warnings();
  j["omitted"] = report.omitted;
  nlohmann::json list = nlohmann::json::array();
  for (const KnittabilityViolation& v : report.violations) {
    nlohmann::json e;
    e["rule"] = std::string(rule_id(v.rule));
    e["severity"] = v.severity == Severity::Error ? "error" : "warning";
    e["message"] = v.message;
    e["stitches"] = v.stitches;
    nlohmann::json cells = nlohmann::json::array();
    for (const GridCell& g : v.cells) cells.push_back({g.row, g.col});
    e["cells"] = std::move(cells);
    e["position"] = {v.position.x(), v.position.y(), v.position.z()};
    list.push_back(std::move(e));
  }
  j["violations"] = std::move(list);
  nlohmann::json counts = nlohmann::json::object();
  for (int i = 0; i < kNumKnitRules; ++i) {
    if (report.counts[i] > 0) counts[std::string(rule_id(static_cast<KnitRule>(i)))] = report.counts[i];
  }
  j["counts"] = std::move(counts);
  return j;
}

namespace {

const nlohmann::json& need(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) {
    throw IOError(fmt::format("knittability report JSON: {} has no \"{}\"", where, key));
  }
  return j.at(key);
}

KnitRule rule_from(const std::string& id, const std::string& where) {
  try {
    return parse_rule_id(id);
  } catch (const InvalidInput&) {
    throw IOError(fmt::format("knittability report JSON: {} names an unknown rule \"{}\"", where, id));
  }
}

}  // namespace

KnittabilityReport knittability_report_from_json(const nlohmann::json& j) {
  KnittabilityReport rep;
  try {
    rep.omitted = need(j, "omitted", "the report").get<int>();
    const nlohmann::json& list = need(j, "violations", "the report");
    if (!list.is_array()) throw IOError("knittability report JSON: \"violations\" is not an array");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string where = fmt::format("violation {}", i);
      const nlohmann::json& e = list[i];
      KnittabilityViolation v;
      v.rule = rule_from(need(e, "rule", where).get<std::string>(), where);
      v.severity = need(e, "severity", where).get<std::string>() == "warning" ? Severity::Warning : Severity::Error;
      v.message = need(e, "message", where).get<std::string>();
      v.stitches = need(e, "stitches", where).get<std::vector<int>>();
      for (const auto& c : need(e, "cells", where)) {
        if (!c.is_array() || c.size() != 2) {
          throw IOError(fmt::format("knittability report JSON: {} has a cell that is not [row, col]", where));
        }
        v.cells.push_back({c[0].get<int>(), c[1].get<int>()});
      }
      const auto p = need(e, "position", where).get<std::vector<double>>();
      if (p.size() != 3) {
        throw IOError(fmt::format("knittability report JSON: {} position is not [x, y, z]", where));
      }
      v.position = Vec3(p[0], p[1], p[2]);
      rep.violations.push_back(std::move(v));
    }
    const nlohmann::json& counts = need(j, "counts", "the report");
    if (!counts.is_object()) throw IOError("knittability report JSON: \"counts\" is not an object");
    for (const auto& [id, n] : counts.items()) {
      rep.counts[static_cast<int>(rule_from(id, "\"counts\""))] = n.get<int>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw IOError(fmt::format("knittability report JSON: wrong value type ({})", e.what()));
  }
  return rep;
}

}  // namespace knitforge
