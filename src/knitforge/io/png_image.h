#pragma once
/// \file png_image.h
/// PNG reading and writing of 8-bit RGB images (render/render_mesh.h
/// RgbImage), with libpng: pictures made by the raster preview.

#include <string>

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

}  // namespace knitforge
