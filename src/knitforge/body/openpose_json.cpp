#include "knitforge/body/openpose_json.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

// BODY_25 index of each COCO-18 keypoint.
constexpr std::array<int, kNumBodyKeypoints> kBody25 = {0, 1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18};

}  // namespace

PersonKeypoints openpose_keypoints_from_json(const nlohmann::json& json, const std::string& what) {
  if (!json.is_object() || !json.contains("people") || !json["people"].is_array())
    throw InvalidInput(fmt::format("{}: no \"people\" array (OpenPose's JSON output is expected)", what));
  const auto& people = json["people"];
  if (people.empty()) throw InvalidInput(fmt::format("{}: \"people\" is empty: no person was detected", what));
  const auto& person = people[0];
  if (!person.is_object() || !person.contains("pose_keypoints_2d") || !person["pose_keypoints_2d"].is_array())
    throw InvalidInput(fmt::format("{}: people[0] has no \"pose_keypoints_2d\" array", what));
  const auto& flat = person["pose_keypoints_2d"];
  if (flat.size() != 54 && flat.size() != 75)
    throw InvalidInput(fmt::format("{}: people[0].pose_keypoints_2d has {} numbers; COCO-18 has 54 (18 x, y, "
                                   "confidence), BODY_25 75",
                                   what, flat.size()));
  const bool body25 = flat.size() == 75;
  PersonKeypoints out;
  out.people_in_file = static_cast<int>(people.size());
  for (int k = 0; k < kNumBodyKeypoints; ++k) {
    const int src = body25 ? kBody25[static_cast<size_t>(k)] : k;
    std::array<double, 3> v{};
    for (int c = 0; c < 3; ++c) {
      const auto& e = flat[static_cast<size_t>(3 * src + c)];
      if (!e.is_number())
        throw InvalidInput(fmt::format("{}: people[0].pose_keypoints_2d[{}] is not a number", what, 3 * src + c));
      v[static_cast<size_t>(c)] = e.get<double>();
    }
    if (!(v[2] > 0)) continue;  // not detected
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || v[0] < 0 || v[1] < 0)
      throw InvalidInput(fmt::format("{}: keypoint '{}' (pose_keypoints_2d[{}]) is at ({}, {}), not a pixel", what,
                                     body_keypoint_names()[static_cast<size_t>(k)], 3 * src, v[0], v[1]));
    out.px[static_cast<size_t>(k)] = Vec2(v[0], v[1]);
    out.present[static_cast<size_t>(k)] = true;
  }
  return out;
}

nlohmann::json openpose_keypoints_to_json(const PersonKeypoints& person) {
  nlohmann::json flat = nlohmann::json::array();
  for (size_t k = 0; k < kNumBodyKeypoints; ++k) {
    flat.push_back(person.present[k] ? person.px[k].x() : 0.0);
    flat.push_back(person.present[k] ? person.px[k].y() : 0.0);
    flat.push_back(person.present[k] ? 1.0 : 0.0);
  }
  return {{"version", 1.3}, {"people", nlohmann::json::array({{{"pose_keypoints_2d", flat}}})}};
}

}  // namespace knitforge
