#pragma once
/// \file yarn_model.h
/// YarnModel: the yarn-level representation (seed §1.2.1, §1.3.3): one
/// directed polyline per yarn (carrier), in knitting order, each vertex tagged
/// with the stitch it belongs to.

#include <vector>

#include "knitforge/geometry/vec.h"

namespace knitforge {

struct Yarn {
  int id = 0;                 ///< yarn / carrier index (as Stitch::yarn)
  std::vector<Vec3> points;   ///< polyline vertices in knitting order (mm)
  std::vector<int> stitch;    ///< stitch index of each vertex (same size as points)
};

struct YarnModel {
  std::vector<Yarn> yarns;
};

}  // namespace knitforge
