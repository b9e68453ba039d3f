// Example 02: checking knittability (seed §1.2.2).
//
// A short-row cup is knittable. Moving one short-row turn so that the two
// turning stitches no longer stack breaks the "short-row ends in pairs" rule
// and the one-stroke continuity; the checker says where.
//
//   build/examples/example_02_knittability
#include <cstdio>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/convert/sample_knitting_map.h"

int main() {
  using namespace knitforge;
  KnittingMap map = cup_knitting_map();
  std::printf("cup: %s\n", check_knittability(map).text().c_str());

  // Find the first short-row-right end and shorten that row by one stitch.
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 1; c < map.cols; ++c) {
      if (map.at(r, c) == CellType::ShortRowRight && map.direction[r] > 0) {
        map.at(r, c) = CellType::Collapsed;
        map.at(r, c - 1) = CellType::ShortRowRight;
        std::printf("moved the turn of course %d from wale %d to %d\n", r, c, c - 1);
        std::printf("%s\n", check_knittability(map).text().c_str());
        return 0;
      }
    }
  }
  return 1;
}
