#pragma once
// Four one-end darts on a hemisphere of radius `sphere_radius` centred at the
// origin (pole on +z): from the rim towards the pole along +x, -x
// (horizontal) and +y, -y (vertical), their tips `tip_radius` from the axis —
// the shape `knitforge flatten hemisphere --auto-darts 4` gives.
#include <cmath>
#include <vector>

#include "knitforge/design/flatten/dart.h"

namespace knitforge {

inline std::vector<DartSpec> hemisphere_rim_darts(double sphere_radius, double tip_radius) {
  std::vector<DartSpec> darts;
  const double r = tip_radius, z = std::sqrt(sphere_radius * sphere_radius - r * r);
  const Vec3 tips[4] = {Vec3(r, 0, z), Vec3(-r, 0, z), Vec3(0, r, z), Vec3(0, -r, z)};
  for (int i = 0; i < 4; ++i) {
    DartSpec d;
    d.type = DartType::OneEnd;
    d.orientation = i < 2 ? DartOrientation::Horizontal : DartOrientation::Vertical;
    d.points = {DartWaypoint::at_position(tips[i])};
    d.to_boundary = true;
    darts.push_back(d);
  }
  return darts;
}

}  // namespace knitforge
