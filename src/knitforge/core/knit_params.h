#pragma once
/// \file knit_params.h
/// The physical scale of a design: the size of one stitch. Every other length
/// scale in knitforge derives from it.

namespace knitforge {

/// Size of a regular stitch in the relaxed fabric, in millimetres.
/// Defaults are the Brother KH868 stitch of the seed (3.5 x 2.8 mm).
struct KnitParams {
  double stitch_width = 3.5;   ///< wale spacing: width of one stitch (mm)
  double stitch_height = 2.8;  ///< course spacing: height of one stitch (mm)
};

}  // namespace knitforge
