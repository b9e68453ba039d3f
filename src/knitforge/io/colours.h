#pragma once
/// \file colours.h
/// The colours knitforge uses in files meant for viewers: stitch-mesh PLY face
/// colours, knitting-map pictures, coloured triangle meshes. One palette, so a
/// stitch type has the same colour everywhere.

#include <cstdint>

#include "knitforge/core/stitch.h"

namespace knitforge {

/// An 8-bit sRGB colour.
struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

/// Colour of a stitch type: Knit light blue, ShortRowLeft orange,
/// ShortRowRight red, Increase green, Decrease purple.
Rgb stitch_type_colour(StitchType t);

/// Background of a knitting-map cell as in the seed's figures: stitch cells
/// light blue in rows knitted left to right (direction +1), darker blue in
/// rows knitted right to left; Collapsed grey; Empty white. Shaping stitches
/// get a glyph of stitch_type_colour() on top of this background.
Rgb map_cell_background(CellType c, int direction);

/// Colour for a non-zero yarn index (a small repeating palette); yarn 0 has no
/// tint.
Rgb yarn_colour(int yarn);

/// `a` mixed with `b`: (1 - t) a + t b, rounded, t in [0, 1].
Rgb mix(Rgb a, Rgb b, double t);

}  // namespace knitforge
