#pragma once
/// \file scalar_colours.h
/// A colour map for per-element values (per-stitch error or distortion as
/// face colours of a PLY file). The evaluate layer sits below io/, so the
/// colour is a plain RGB triple here (io's Rgb has the same layout).
///
/// The map is viridis (matplotlib's perceptually uniform, colour-blind safe
/// map) sampled at 9 equally spaced points and interpolated linearly:
/// dark purple (68, 1, 84) at `lo`, through blue and green, to yellow
/// (253, 231, 37) at `hi`. Values outside [lo, hi] get the end colours.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace knitforge {

/// 8-bit sRGB red, green, blue.
using Rgb8 = std::array<uint8_t, 3>;

/// Colour of value v on [lo, hi] (see the file comment); lo == hi maps every
/// value to the `lo` colour.
/// \throw InvalidInput when v, lo or hi is not finite or lo > hi.
Rgb8 viridis_colour(double v, double lo, double hi);

/// viridis_colour() of every value, on [lo, hi].
/// \throw as viridis_colour().
std::vector<Rgb8> scalar_colours(std::span<const double> values, double lo, double hi);

/// viridis_colour() of every value on [0, max(values)] (all `lo` colour when
/// every value is 0 or there are none): the default for errors and
/// distortions, which are >= 0.
/// \throw InvalidInput for a negative or non-finite value.
std::vector<Rgb8> scalar_colours(std::span<const double> values);

}  // namespace knitforge
