#pragma once
// Hand-made knitting maps for the machine tests (drawn top row first, see
// tests/convert/map_test_helpers.h: K knit, L/R short-row ends, I increase,
// D decrease, '.' collapsed, '_' empty; row 0 goes left to right).

#include <string>
#include <utility>
#include <vector>

#include "convert/map_test_helpers.h"

namespace knitforge::test {

inline KnittingMap rectangle_map() {
  return parse_map({"KKKKKK", "KKKKKK", "KKKKKK", "KKKKKK"});
}

// Rows 1 and 2 are a short row turning at column 2 on the left (wales 0, 1 held).
inline KnittingMap short_row_wedge_map() {
  return parse_map({"KKKKKK", "..LKKK", "..LKKK", "KKKKKK"});
}

// A short column starting at row 1 in column 2 and running to the top.
inline KnittingMap one_increase_map() {
  return parse_map({"KKKKK", "KKKKK", "KKIKK", "KK.KK"});
}

// A short column ending at row 2 in column 2 (the bottom edge starts it).
inline KnittingMap one_decrease_map() {
  return parse_map({"KK.KK", "KKDKK", "KKKKK", "KKKKK"});
}

// A short column with both ends inside, right of centre.
inline KnittingMap short_column_map() {
  return parse_map({"KKKK.KK", "KKKKDKK", "KKKKKKK", "KKKKKKK", "KKKKIKK", "KKKK.KK"});
}

// The fabric widens by one wale on each side, then narrows again; each
// course widens or narrows at its end, where the carriage turns (a course
// that started beyond the last stitch of the one below would break the
// one-stroke order, seed §1.2.2).
inline KnittingMap boundary_shaping_map() {
  return parse_map({"_KKKK__", "_KKKK__", "_KKKKK_", "KKKKKK_", "KKKKK__", "_KKKK__"});
}

// Fourteen increases in one course: far wales move more than 4 needles.
inline KnittingMap many_increases_map() {
  std::string r0, r1, r2;
  for (int i = 0; i < 29; ++i) {
    r0 += i % 2 ? '.' : 'K';
    r1 += i % 2 ? 'I' : 'K';
    r2 += 'K';
  }
  return parse_map({r2, r2, r1, r0});
}

inline std::vector<std::pair<std::string, KnittingMap>> hand_made_maps() {
  return {{"rectangle", rectangle_map()},          {"short-row wedge", short_row_wedge_map()},
          {"one increase", one_increase_map()},    {"one decrease", one_decrease_map()},
          {"short column", short_column_map()},    {"boundary shaping", boundary_shaping_map()},
          {"many increases", many_increases_map()}};
}

}  // namespace knitforge::test
