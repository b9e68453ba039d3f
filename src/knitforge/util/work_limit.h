#pragma once
/// \file work_limit.h
/// Bounded cost, told up front: every route estimates its work before it
/// allocates (stitches from area / (stitch width x stitch height), cells of
/// a grid, lines of a program, ...) and refuses beyond a documented limit
/// with a message that gives the estimate, what it would take, and how to
/// override. The limits and the memory per unit are listed in
/// docs/user-guide.md ("Limits"); the CLI's --max-stitches sets the stitch
/// limit of a run.
#include <cstdint>
#include <string>
#include <string_view>

namespace knitforge {

/// Default limit on the stitches of one design run (`--max-stitches`). A
/// garment front at 3.5 x 2.8 mm is ~30k stitches, a fine-gauge sweater
/// (1.25 x 1.0 mm) ~500k; the short-row route needs ~2.5 kB per stitch.
inline constexpr double kDefaultMaxStitches = 1e6;

/// What one unit of a work estimate costs, for the message.
struct WorkEstimate {
  std::string_view what;        ///< e.g. "the surface"
  double count = 0.0;           ///< estimated units (stitches, cells, lines, faces)
  std::string_view unit;        ///< "stitches", "cells", ...
  double limit = 0.0;           ///< refuse above this
  double bytes_per_unit = 0.0;  ///< memory estimate per unit (0: not stated)
  /// How to override or avoid it, e.g. "raise the limit with --max-stitches N".
  std::string_view remedy;
};

/// Throws when e.count exceeds e.limit (or is not finite):
/// "<what> would need about N <unit> (about M GB), more than the limit of L;
/// <remedy>". Numbers are printed readably (1.2 million, 3.4e+12).
/// \throw InvalidInput as described; also when the limit is not positive.
void check_work(const WorkEstimate& e);

/// A count printed for people: "1,234", "12.3 million", "4.5e+12".
std::string readable_count(double n);

/// A byte count printed for people: "512 kB", "1.5 GB".
std::string readable_bytes(double bytes);

}  // namespace knitforge
