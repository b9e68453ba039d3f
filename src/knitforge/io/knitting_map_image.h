#pragma once
/// \file knitting_map_image.h
/// Pictures of a knitting map drawn like the seed's figures (e.g. Fig. 1.5,
/// 3.5): one square cell per stitch, row 0 at the bottom; stitch cells of rows
/// knitted left to right light blue, of rows knitted right to left darker
/// blue (map_cell_background() in colours.h); Collapsed cells grey, Empty
/// cells white; shaping stitches carry a triangle pointing to their apex
/// (ShortRowLeft to the left, ShortRowRight to the right, Increase down,
/// Decrease up) in stitch_type_colour(); thin grid lines between cells. A
/// stitch of a non-zero yarn is tinted with yarn_colour(). The SVG adds course
/// and wale index labels every 10 cells and a legend. A tube (docs/tubes.md)
/// adds the fold between its front and back halves (a dark double line) and
/// each round's seam (its grid line in red); the SVG labels the halves.

#include <string>

#include "knitforge/core/knitting_map.h"

namespace knitforge {

struct MapImageOptions {
  /// Size of one cell in pixels (PNG) or SVG user units, including its grid
  /// line; at least 4. Default 12.
  int cell_size = 12;
  /// Tint stitches of non-zero yarns (jacquard / intarsia maps).
  bool yarn_tint = true;
};

/// PNG geometry: the picture is cols*cell_size+1 by rows*cell_size+1 pixels.
/// Cell (r, c) spans x in [c*s, (c+1)*s] and y in [(rows-1-r)*s, (rows-r)*s]
/// (y down, so row 0 is at the bottom); its border pixels are grid lines.
/// \throw InvalidInput for an inconsistent map, cell_size < 4, or a picture
///        of more than 2^27 pixels (use a smaller cell size or the SVG).
/// \throw IOError when the file cannot be written.
void write_knitting_map_png(const std::string& path, const KnittingMap& map, const MapImageOptions& options = {});

/// The SVG document: one `<rect class="cell">` per map cell, one
/// `<polygon class="glyph">` per shaping stitch, labels and a legend.
/// \throw InvalidInput for an inconsistent map or cell_size < 4.
std::string knitting_map_svg(const KnittingMap& map, const MapImageOptions& options = {});

/// Writes knitting_map_svg() to `path` atomically.
/// \throw InvalidInput as knitting_map_svg(); IOError when writing fails.
void write_knitting_map_svg(const std::string& path, const KnittingMap& map, const MapImageOptions& options = {});

/// Dispatches on the extension of `path`: .png or .svg.
/// \throw InvalidInput for another extension, and as the writers above.
void write_knitting_map_image(const std::string& path, const KnittingMap& map,
                              const MapImageOptions& options = {});

}  // namespace knitforge
