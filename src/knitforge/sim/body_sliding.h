#pragma once
/// \file body_sliding.h
/// How far the garment slides over the body (docs/sim.md, "Garments on a
/// moving body"): per fabric vertex, the displacement of its contact point
/// on the body from the point where it first touched, measured on the body.
///
/// A vertex touches when its closest body point is within `near_mm` (the
/// contact distance or a little more). The first time it touches, that body
/// point (face, barycentrics) becomes its anchor; the anchor moves with the
/// body. At every later update in which it touches, its sliding is the
/// distance between its current closest body point and the anchor (both on
/// the body at its current pose): the chord, which for slides short against
/// the body's radius of curvature is the tangential displacement. While it
/// does not touch, its sliding keeps the last value. A vertex worn touching
/// the body at t = 0 is anchored there; a garment carried rigidly with the
/// body slides 0 (test).

#include <vector>

#include <Eigen/Core>

#include "knitforge/sim/kinematic_body.h"

namespace knitforge {

struct BodySliding {
  std::vector<int> anchor_face;       ///< per vertex, -1 before the first touch
  std::vector<Vec3> anchor_bary;      ///< per vertex
  std::vector<double> sliding_mm;     ///< per vertex, 0 before the first touch
  std::vector<double> max_sliding_mm; ///< per vertex, the largest so far
  std::vector<char> touching;         ///< per vertex, at the last update
};

/// Starts the measure for n vertices (no anchors).
BodySliding start_body_sliding(int num_vertices);

/// Updates `s` with positions x (3n, mm) against `body` at its current pose.
/// \throw InvalidInput when x's size does not match or near_mm is not positive.
void update_body_sliding(BodySliding& s, const KinematicBody& body, const Eigen::VectorXd& x, double near_mm);

}  // namespace knitforge
