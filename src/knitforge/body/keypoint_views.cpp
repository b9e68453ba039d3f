#include "knitforge/body/keypoint_views.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/json_values.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using json_values::field;

std::vector<KeypointView> keypoint_views_from_json(const nlohmann::json& json, const std::string& what) {
  double scale = 1.0;
  if (json.is_object() && json.contains("units")) {
    const auto& u = json.at("units");
    const std::string units = u.is_string() ? u.get<std::string>() : u.dump();
    if (units == "mm") scale = 1.0;
    else if (units == "cm") scale = 10.0;
    else if (units == "m") scale = 1000.0;
    else throw InvalidInput(fmt::format("{}: units \"{}\" unknown; use mm, cm or m", what, units));
  }
  const auto& cams = field(json, "cameras", what);
  if (!cams.is_array() || cams.empty()) throw InvalidInput(fmt::format("{}: \"cameras\" must be a non-empty array", what));
  std::vector<KeypointView> views;
  for (size_t c = 0; c < cams.size(); ++c) {
    const auto& jc = cams[c];
    KeypointView v;
    v.name = jc.is_object() && jc.contains("name") && jc.at("name").is_string() ? jc.at("name").get<std::string>()
                                                                                : fmt::format("{}", c);
    const std::string where = fmt::format("{}: camera {} ('{}')", what, c, v.name);
    v.camera.K = json_values::mat3(field(jc, "K", where), where + " K");
    v.camera.R = json_values::rotation(field(jc, "R", where), where + ": R");
    v.camera.t = scale * json_values::vec3(field(jc, "t", where), where + " t");
    if (!(std::abs(v.camera.K.determinant()) > 0.0))
      throw InvalidInput(fmt::format("{}: the intrinsic matrix K is singular", where));
    const auto& kp = field(jc, "keypoints", where);
    if (!kp.is_object()) throw InvalidInput(fmt::format("{}: \"keypoints\" must be an object of name: [u, v]", where));
    for (const auto& [name, uv] : kp.items()) v.keypoints[name] = json_values::vec2(uv, where + " keypoint " + name);
    views.push_back(std::move(v));
  }
  return views;
}

TriangulatedKeypoints triangulate_keypoints(const std::vector<KeypointView>& views) {
  std::map<std::string, std::vector<Ray>> rays;
  for (const KeypointView& v : views)
    for (const auto& [name, px] : v.keypoints) rays[name].push_back(camera_ray(v.camera, px));
  TriangulatedKeypoints out;
  for (const auto& [name, rs] : rays) {
    if (rs.size() < 2) {
      out.skipped.push_back(name);
      continue;
    }
    try {
      const RayPoint p = triangulate_rays(rs);
      out.points[name] = {p.point, static_cast<int>(rs.size()), p.rms_distance_mm};
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("keypoint '{}': {}", name, e.what()));
    }
  }
  return out;
}

}  // namespace knitforge
