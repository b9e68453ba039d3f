#pragma once
/// \file png_image.h
/// PNG reading and writing with libpng: 8-bit RGB images (render/render_mesh.h
/// RgbImage), pictures made by the raster preview; and 16-bit greyscale
/// images (Gray16Image), the depth images of depth cameras
/// (body/depth_image.h).

#include <cstdint>
#include <string>
#include <vector>

#include "knitforge/render/render_mesh.h"

namespace knitforge {

/// Writes `image` as an 8-bit RGB PNG, atomically.
/// \throw InvalidInput when the size is not positive or the pixel array does
///        not hold width * height * 3 bytes; IOError when encoding or
///        writing fails.
void write_png(const std::string& path, const RgbImage& image);

/// Reads a PNG (any bit depth and colour type; converted to 8-bit RGB, alpha
/// dropped, palette and grey expanded).
/// \throw IOError naming the file when it is missing or not a valid PNG.
RgbImage read_png(const std::string& path);

/// A 16-bit single-channel image, row-major (pixel (u, v) at v * width + u).
struct Gray16Image {
  int width = 0;
  int height = 0;
  std::vector<uint16_t> pixels;
};

/// Writes `image` as a 16-bit greyscale PNG (lossless), atomically.
/// \throw InvalidInput when the size is not positive or the pixel array does
///        not hold width * height values; IOError when encoding or writing fails.
void write_png_gray16(const std::string& path, const Gray16Image& image);

/// Reads a 16-bit greyscale PNG exactly as stored (no conversion: a depth
/// image's values must not be rescaled or gamma-corrected).
/// \throw IOError naming the file when it is missing or not a valid PNG, and
///        when it is a PNG of another kind ("8-bit RGB PNG; a depth image
///        is a 16-bit greyscale PNG").
Gray16Image read_png_gray16(const std::string& path);

}  // namespace knitforge
