#pragma once
// The dart of the worked example (docs/examples/saddle_darts.json): a
// vertical two-end dart through the centre of the monkey saddle, from
// (0, -20, 0) to (0, 20, 0) mm.
#include "knitforge/design/flatten/dart.h"

namespace knitforge {

inline DartSpec saddle_two_end_dart() {
  DartSpec d;
  d.type = DartType::TwoEnd;
  d.orientation = DartOrientation::Vertical;
  d.points = {DartWaypoint::at_position(Vec3(0, -20, 0)), DartWaypoint::at_position(Vec3(0, 20, 0))};
  return d;
}

}  // namespace knitforge
