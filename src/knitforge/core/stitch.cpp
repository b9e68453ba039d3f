#include "knitforge/core/stitch.h"

namespace knitforge {

namespace {
constexpr Side kKnit[] = {Side::Bottom, Side::Right, Side::Top, Side::Left};
constexpr Side kLeft[] = {Side::Bottom, Side::Right, Side::Top};
constexpr Side kRight[] = {Side::Bottom, Side::Top, Side::Left};
constexpr Side kInc[] = {Side::Right, Side::Top, Side::Left};
constexpr Side kDec[] = {Side::Bottom, Side::Right, Side::Left};
constexpr std::string_view kNames[] = {"knit",     "short-row-left", "short-row-right", "increase",
                                       "decrease", "collapsed",      "empty"};
}  // namespace

std::span<const Side> edge_sides(StitchType t) {
  switch (t) {
    case StitchType::Knit: return kKnit;
    case StitchType::ShortRowLeft: return kLeft;
    case StitchType::ShortRowRight: return kRight;
    case StitchType::Increase: return kInc;
    case StitchType::Decrease: return kDec;
  }
  return kKnit;
}

int edge_of_side(StitchType t, Side s) {
  const auto sides = edge_sides(t);
  for (size_t k = 0; k < sides.size(); ++k) {
    if (sides[k] == s) return static_cast<int>(k);
  }
  return -1;
}

int apex_corner(StitchType t) {
  switch (t) {
    case StitchType::Knit: return -1;
    case StitchType::ShortRowLeft: return 0;
    case StitchType::ShortRowRight: return 1;
    case StitchType::Increase: return 0;
    case StitchType::Decrease: return 2;
  }
  return -1;
}

std::string_view name(StitchType t) { return kNames[static_cast<int>(t)]; }
std::string_view name(CellType c) { return kNames[static_cast<int>(c)]; }

std::optional<StitchType> parse_stitch_type(std::string_view s) {
  for (int i = 0; i < kNumStitchTypes; ++i) {
    if (kNames[i] == s) return static_cast<StitchType>(i);
  }
  return std::nullopt;
}

}  // namespace knitforge
