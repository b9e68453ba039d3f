#include "knitforge/io/colours.h"

#include <cmath>

namespace knitforge {

namespace {
constexpr Rgb kLightBlue{166, 206, 227};
constexpr Rgb kDarkBlue{31, 120, 180};
constexpr Rgb kGrey{170, 170, 170};
constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kStitch[kNumStitchTypes] = {
    kLightBlue,       // Knit
    {255, 127, 0},    // ShortRowLeft
    {227, 26, 28},    // ShortRowRight
    {51, 160, 44},    // Increase
    {106, 61, 154},   // Decrease
};
constexpr Rgb kYarn[] = {{255, 217, 47}, {231, 41, 138}, {27, 158, 119}, {166, 86, 40}, {102, 102, 102}};
}  // namespace

Rgb stitch_type_colour(StitchType t) {
  const int i = static_cast<int>(t);
  return i >= 0 && i < kNumStitchTypes ? kStitch[i] : kWhite;
}

Rgb map_cell_background(CellType c, int direction) {
  if (c == CellType::Empty) return kWhite;
  if (c == CellType::Collapsed) return kGrey;
  return direction < 0 ? kDarkBlue : kLightBlue;
}

Rgb yarn_colour(int yarn) {
  if (yarn <= 0) return kWhite;
  return kYarn[(yarn - 1) % static_cast<int>(std::size(kYarn))];
}

Rgb mix(Rgb a, Rgb b, double t) {
  auto ch = [t](uint8_t x, uint8_t y) {
    return static_cast<uint8_t>(std::lround((1.0 - t) * x + t * y));
  };
  return {ch(a.r, b.r), ch(a.g, b.g), ch(a.b, b.b)};
}

}  // namespace knitforge
