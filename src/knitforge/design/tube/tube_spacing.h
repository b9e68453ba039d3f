#pragma once
/// \file tube_spacing.h
/// How far apart the rounds of a tube lie at each place round it
/// (docs/tubes.md, "Short rows in a bend"). On a bent tube the levels of the
/// tube field are closer on the inside of the bend than on the outside
/// ((R - r)/(R + r) on a torus piece), so rounds one stitch height apart on
/// average make short stitches inside and tall ones outside.
///
/// The table: `levels` + 1 rounds at u = j / levels (tube_round_curves(),
/// all started by the same chain so that a fraction of the arc length from
/// the start is the same place round the tube on every round), each sampled
/// at `fractions` points f = i / fractions of its arc length; along[i][j] is
/// the distance walked from the start rim to round j along the points of
/// fraction i (the sum of the steps between consecutive rounds). The
/// inside line is the fraction whose rim-to-rim distance is the smallest,
/// the outside line the largest.
///
/// measure_course_spacing() reads a tube's stitch mesh against the table:
/// the heights of the Knit stitches along the inside and along the outside
/// line, and of all of them (a stitch's height: from the middle of its bottom
/// side to the middle of its top side, without the part along the course),
/// over the stitch height. Deterministic.

#include <optional>
#include <vector>

#include "knitforge/core/stitch_mesh.h"
#include "knitforge/design/tube/tube_field.h"
#include "knitforge/design/tube/tube_rounds.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Distance between the levels of a tube field, per place round the tube.
struct TubeSpacing {
  int levels = 0, fractions = 0;
  std::vector<RoundCurve> curves;          ///< levels + 1 rounds at u = j / levels
  std::vector<std::vector<double>> along;  ///< [fraction i][level j], mm from the start rim
  std::vector<double> inside;              ///< per level j: min over i of along[i][j] (mm)
  int inside_fraction = 0, outside_fraction = 0;  ///< i of the smallest / largest rim-to-rim distance
  double ratio = 1.0;  ///< largest over smallest rim-to-rim distance (1 on a straight tube)

  /// along at fraction f (0..1, cyclic) and field value u, interpolated.
  double along_at(double f, double u) const;
  /// inside at field value u, interpolated.
  double inside_at(double u) const;
  /// u where inside_at(u) = d (0 <= d <= inside.back()).
  double level_of_inside(double d) const;
  /// u where along_at(f, u) = d (clamped to the rims).
  double level_at(double f, double d) const;
  /// The point at fraction f of the level u, between the table's rounds.
  Vec3 point(double f, double u) const;
  /// The points of fraction i on every round (a line from rim to rim).
  std::vector<Vec3> line(int i) const;
};

/// Builds the table (see the file comment).
/// \pre levels >= 2, fractions >= 4.
/// \throw InvalidInput as tube_round_curves() when a level is not one loop.
TubeSpacing tube_spacing(const TriMesh& mesh, const TubeField& field, int levels, int fractions,
                         const std::optional<Vec3>& start = std::nullopt);

/// Heights of the stitches along one line, over the stitch height.
struct SideSpacing {
  int stitches = 0;         ///< Knit stitches whose centre lies within a stitch width of the line
  double min = 0, max = 0;  ///< their smallest and largest height / sh
  int taller = 0;           ///< of them, taller than 1.25 sh
};

/// The course spacing of a tube's stitch mesh along the inside and the
/// outside line of `spacing`.
struct CourseSpacing {
  SideSpacing inside, outside;
  SideSpacing all;  ///< every Knit stitch of the mesh
};

CourseSpacing measure_course_spacing(const StitchMesh& mesh, const TubeSpacing& spacing, double stitch_width,
                                     double stitch_height);

}  // namespace knitforge
