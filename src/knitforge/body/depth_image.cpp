#include "knitforge/body/depth_image.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/body/json_values.h"
#include "knitforge/io/png_image.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

void check_size(const DepthImage& image, const DepthCamera& camera, const std::string& what) {
  if (image.width != camera.width || image.height != camera.height ||
      image.depth_mm.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height))
    throw InvalidInput(fmt::format("{}: a {}x{} depth image ({} values) for a {}x{} camera; give the intrinsics of "
                                   "the camera that took it",
                                   what, image.width, image.height, image.depth_mm.size(), camera.width,
                                   camera.height));
}

}  // namespace

DepthCamera depth_camera_from_json(const nlohmann::json& json, const std::string& what) {
  if (!json.is_object()) throw InvalidInput(fmt::format("{}: expected a JSON object with width, height, K", what));
  for (const auto& [key, value] : json.items()) {
    if (key != "width" && key != "height" && key != "K" && key != "depth_unit_mm" && key != "name")
      throw InvalidInput(fmt::format("{}: unknown key \"{}\" (known: width, height, K, depth_unit_mm, name)", what, key));
  }
  DepthCamera c;
  c.width = json_values::integer(json_values::field(json, "width", what), what + ": width", 1, 65535);
  c.height = json_values::integer(json_values::field(json, "height", what), what + ": height", 1, 65535);
  c.K = json_values::mat3(json_values::field(json, "K", what), what + ": K");
  if (c.K(1, 0) != 0.0 || c.K(2, 0) != 0.0 || c.K(2, 1) != 0.0 || c.K(2, 2) != 1.0 || !(c.K(0, 0) > 0.0) ||
      !(c.K(1, 1) > 0.0))
    throw InvalidInput(fmt::format("{}: K must be [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0 (pixels)", what));
  if (json.contains("depth_unit_mm")) {
    c.depth_unit_mm = json_values::number(json.at("depth_unit_mm"), what + ": depth_unit_mm");
    if (!(c.depth_unit_mm > 0.0))
      throw InvalidInput(fmt::format("{}: depth_unit_mm must be positive (1 for a Kinect's millimetres)", what));
  }
  return c;
}

nlohmann::json depth_camera_to_json(const DepthCamera& camera) {
  return {{"width", camera.width},
          {"height", camera.height},
          {"K", json_values::to_json(camera.K)},
          {"depth_unit_mm", camera.depth_unit_mm}};
}

DepthImage read_depth_image(const std::string& path, const DepthCamera& camera) {
  const Gray16Image png = read_png_gray16(path);
  DepthImage image{png.width, png.height, std::vector<double>(png.pixels.size())};
  for (size_t i = 0; i < png.pixels.size(); ++i) image.depth_mm[i] = png.pixels[i] * camera.depth_unit_mm;
  check_size(image, camera, path);
  return image;
}

void write_depth_image(const std::string& path, const DepthImage& image, const DepthCamera& camera) {
  check_size(image, camera, path);
  Gray16Image png{image.width, image.height, std::vector<uint16_t>(image.depth_mm.size())};
  for (size_t i = 0; i < image.depth_mm.size(); ++i) {
    const double z = image.depth_mm[i];
    const double units = std::round(z / camera.depth_unit_mm);
    if (!std::isfinite(z) || z < 0.0 || units > 65535.0)
      throw InvalidInput(fmt::format("{}: pixel ({}, {}) has depth {} mm; a depth must be finite, >= 0 and at most "
                                     "65535 units ({:g} mm at {:g} mm per unit)",
                                     path, i % static_cast<size_t>(image.width), i / static_cast<size_t>(image.width),
                                     z, 65535.0 * camera.depth_unit_mm, camera.depth_unit_mm));
    png.pixels[i] = static_cast<uint16_t>(z > 0.0 && units < 1.0 ? 1.0 : units);
  }
  write_png_gray16(path, png);
}

Vec3 back_project(const DepthCamera& camera, double u, double v, double depth_mm) {
  // K upper triangular: solve K x = (u, v, 1) by back substitution.
  const Mat3& K = camera.K;
  const double y = (v - K(1, 2)) / K(1, 1);
  const double x = (u - K(0, 2) - K(0, 1) * y) / K(0, 0);
  return depth_mm * Vec3(x, y, 1.0);
}

std::vector<Vec3> depth_to_points(const DepthImage& image, const DepthCamera& camera, const DepthRange& range,
                                  std::vector<int>* pixels) {
  check_size(image, camera, "depth image");
  std::vector<Vec3> points;
  if (pixels) pixels->clear();
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const double z = image.at(u, v);
      if (!(z > range.min_mm) || !(z <= range.max_mm)) continue;
      points.push_back(back_project(camera, u, v, z));
      if (pixels) pixels->push_back(v * image.width + u);
    }
  }
  return points;
}

}  // namespace knitforge
