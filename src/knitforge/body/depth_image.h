#pragma once
/// \file depth_image.h
/// Depth images of a depth camera (Kinect, RealSense; seed §5.3) and the
/// points they measure.
///
/// A depth camera is a pinhole camera (triangulate_rays.h's convention: the
/// camera looks along +z of its frame, image u to the right and v down)
/// whose every pixel holds the **z-depth** of what it sees, i.e. the z
/// coordinate of the point in the camera's frame (not the distance along
/// the ray); 0 means no measurement. Pixel (u, v) (integers, row v, column
/// u) sees the point  x_c = z K^-1 (u, v, 1)^T  (pixel centres at integer
/// coordinates, as OpenCV and the Kinect SDKs).
///
/// On disk a depth image is a 16-bit greyscale PNG of depth units plus the
/// camera's intrinsics JSON (docs/formats.md):
///
///   { "width": 480, "height": 640,
///     "K": [[320, 0, 239.5], [0, 320, 319.5], [0, 0, 1]],
///     "depth_unit_mm": 1.0 }
///
/// depth_unit_mm is what one PNG unit is (Kinect v2 / Azure: 1 mm;
/// RealSense: its depth scale, 1 mm by default); the deepest storable
/// depth is 65535 units.

#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knitforge/geometry/vec.h"

namespace knitforge {

/// The intrinsics of a depth camera.
struct DepthCamera {
  int width = 0;                ///< pixels (1..65535)
  int height = 0;               ///< pixels (1..65535)
  Mat3 K = Mat3::Identity();    ///< [fx s cx; 0 fy cy; 0 0 1] (pixels)
  double depth_unit_mm = 1.0;   ///< one PNG unit (mm), > 0
};

/// A depth image in millimetres: z-depth per pixel, row-major (pixel (u, v)
/// at v * width + u); 0 = no measurement.
struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<double> depth_mm;

  double at(int u, int v) const { return depth_mm[static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u)]; }
};

/// The intrinsics from JSON; `what` (a file name) names the source in messages.
/// \throw InvalidInput naming `what` and the field when one is missing or
///        malformed: width/height not whole numbers in 1..65535, K not 3 x 3
///        of the form [fx s cx; 0 fy cy; 0 0 1] with fx, fy > 0, depth_unit_mm
///        not positive; unknown keys are refused (a misspelt key would
///        otherwise be silently ignored).
DepthCamera depth_camera_from_json(const nlohmann::json& json, const std::string& what);

/// The JSON depth_camera_from_json() reads.
nlohmann::json depth_camera_to_json(const DepthCamera& camera);

/// Reads a depth image (16-bit greyscale PNG) taken by `camera`: each value
/// times camera.depth_unit_mm.
/// \throw IOError for a missing file or a PNG of another kind (bit depth,
///        colour type, named); InvalidInput when its size is not the
///        camera's (both named).
DepthImage read_depth_image(const std::string& path, const DepthCamera& camera);

/// Writes `image` as a 16-bit PNG of camera.depth_unit_mm units (each depth
/// rounded to the nearest unit; a positive depth never rounds to 0),
/// atomically.
/// \throw InvalidInput when the size is not the camera's, a depth is
///        negative or not finite, or deeper than 65535 units (naming the
///        pixel and what the unit allows).
void write_depth_image(const std::string& path, const DepthImage& image, const DepthCamera& camera);

/// Which depths count as measurements (mm): min < z <= max. A range crops
/// the background (floor, walls) away from the object of interest.
struct DepthRange {
  double min_mm = 0.0;
  double max_mm = std::numeric_limits<double>::infinity();
};

/// The point seen by pixel (u, v) at z-depth `depth_mm`, in the camera's
/// frame (mm): depth_mm * K^-1 (u, v, 1)^T.
Vec3 back_project(const DepthCamera& camera, double u, double v, double depth_mm);

/// The points of every measured pixel within `range`, in the camera's frame
/// (mm), in pixel order (row by row). `pixels` (optional) receives each
/// point's pixel index v * width + u.
/// \throw InvalidInput when the image's size is not the camera's.
std::vector<Vec3> depth_to_points(const DepthImage& image, const DepthCamera& camera, const DepthRange& range = {},
                                  std::vector<int>* pixels = nullptr);

}  // namespace knitforge
