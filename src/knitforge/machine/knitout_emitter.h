#pragma once
/// \file knitout_emitter.h
/// Internal to the knitout writers (knitout_writer.cpp, knitout_tube_writer.cpp):
/// appends knitout operations to a program text, keeps the racking and counts
/// what it writes in KnitoutStats. Not a public API.

#include <cstdlib>
#include <iterator>
#include <string>

#include <optional>
#include <set>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge::writer_detail {

inline char dir_char(int d) { return d > 0 ? '+' : '-'; }

class Emitter {
 public:
  Emitter(const MachineProfile& p, KnitoutStats& s) : prof_(p), stats_(s) {}

  std::string out;
  bool fabric = false;  ///< transfers now count as shaping transfers

  template <typename... Args>
  void line(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(out), f, std::forward<Args>(args)...);
    out.push_back('\n');
  }
  void comment(const std::string& text) { line("; {}", text); }
  /// The header lines (knitout_writer.h, layout 1).
  void headers(const KnitoutOptions& opt) {
    line(";!knitout-2");
    line(";;Machine: {}", prof_.knitout_machine);
    line(";;Gauge: {}", opt.gauge > 0 ? opt.gauge : prof_.gauge);
    if (prof_.width_header) line(";;Width: {}", prof_.needle_count);
    line(";;Carriers: {}", fmt::join(prof_.carriers, " "));
    line(";;Position: {}", opt.position);
  }

  void knit(int d, int n, const std::string& cs) {
    line("knit {} f{} {}", dir_char(d), n, cs);
    ++stats_.knits;
  }
  void tuck(int d, int n, const std::string& cs) {
    line("tuck {} f{} {}", dir_char(d), n, cs);
    ++stats_.tucks;
  }
  void miss(int d, int n, const std::string& cs) { line("miss {} f{} {}", dir_char(d), n, cs); }
  void rack(int r) {
    if (r == racking_) return;
    if (std::abs(r) > prof_.max_racking)
      throw Error(fmt::format("internal: racking {} beyond the machine limit {}", r, prof_.max_racking));
    line("rack {}", r);
    racking_ = r;
    ++stats_.racks;
  }
  void xfer_to_back(int n) {
    line("xfer f{} b{}", n, n);
    count_xfer();
  }
  void xfer_to_front(int n, int to) {
    line("xfer b{} f{}", n, to);
    count_xfer();
  }
  // Bed-aware operations (tubes): `back` selects the back bed.
  void knit_on(int d, bool back, int n, const std::string& cs) {
    line("knit {} {}{} {}", dir_char(d), back ? 'b' : 'f', n, cs);
    ++stats_.knits;
  }
  void tuck_on(int d, bool back, int n, const std::string& cs) {
    line("tuck {} {}{} {}", dir_char(d), back ? 'b' : 'f', n, cs);
    ++stats_.tucks;
  }
  void miss_on(int d, bool back, int n, const std::string& cs) {
    line("miss {} {}{} {}", dir_char(d), back ? 'b' : 'f', n, cs);
  }
  // xfer between the beds at the current racking (the caller racks).
  void xfer(bool from_back, int n, int m) {
    line("xfer {}{} {}{}", from_back ? 'b' : 'f', n, from_back ? 'f' : 'b', m);
    count_xfer();
  }
  // Moves the loops of front needle n onto front needle n + d (|d| <= max racking).
  void move_loops(int n, int d) {
    rack(0);
    xfer_to_back(n);
    rack(d);
    xfer_to_front(n, n + d);
    rack(0);
    stats_.transfer_passes += 2;
  }
  void carrier_in(const std::string& c) { line("{} {}", prof_.has_yarn_inserting_hook ? "inhook" : "in", c); }
  void release(const std::string& c) {
    if (prof_.has_yarn_inserting_hook) line("releasehook {}", c);
  }
  void carrier_out(const std::string& c) {
    line("{} {}", prof_.has_yarn_inserting_hook ? "outhook" : "out", c);
  }
  // Knit a plain pass over needles lo..hi in direction d.
  void knit_pass(int d, int lo, int hi, const std::string& c) {
    if (d > 0)
      for (int n = lo; n <= hi; ++n) knit(d, n, c);
    else
      for (int n = hi; n >= lo; --n) knit(d, n, c);
  }
  // Alternating tuck cast-on over lo..hi starting in direction d: every other
  // needle from the far end of the pass, then the others back. Leaves the
  // carrier beyond the end it started from.
  void tuck_cast_on(int d, int lo, int hi, const std::string& c) {
    if (d < 0) {
      for (int n = hi; n >= lo; n -= 2) tuck(-1, n, c);
      for (int n = lo; n <= hi; ++n)
        if ((hi - n) % 2 != 0) tuck(+1, n, c);
    } else {
      for (int n = lo; n <= hi; n += 2) tuck(+1, n, c);
      for (int n = hi; n >= lo; --n)
        if ((n - lo) % 2 != 0) tuck(-1, n, c);
    }
  }
  void settings(const SectionSettings& s) {
    if (!s.stitch_number.empty()) line("x-stitch-number {}", s.stitch_number);
    if (!s.xfer_stitch_number.empty()) line("x-xfer-stitch-number {}", s.xfer_stitch_number);
    if (s.speed_number >= 0) line("x-speed-number {}", s.speed_number);
    if (s.roller_advance >= 0) line("x-roller-advance {}", s.roller_advance);
  }

 private:
  void count_xfer() {
    ++stats_.xfers;
    if (fabric) ++stats_.shaping_xfers;
  }
  const MachineProfile& prof_;
  KnitoutStats& stats_;
  int racking_ = 0;
};

/// Refuses a layout with problems: the first one's message, and how many more.
/// \throw InvalidInput when `problems` is not empty.
inline void refuse_layout_problems(const MachineProfile& prof, const std::vector<LayoutProblem>& problems,
                                   const char* what) {
  if (problems.empty()) return;
  throw InvalidInput(fmt::format("machine '{}' cannot knit this {}: {}{}", prof.name, what, problems.front().message,
                                 problems.size() > 1 ? fmt::format(" ({} more such places)", problems.size() - 1)
                                                     : std::string()));
}

/// The shift that centres layout needles [min_needle, max_needle] on the
/// machine's bed (needles numbered from 1). \throw InvalidInput when the
/// layout is wider than the bed: "`what` needs N needles at its widest
/// (`counted`); machine 'M' has K".
inline int centred_needle_offset(const MachineProfile& prof, int min_needle, int max_needle, const char* what,
                                 const char* counted) {
  const int width = max_needle - min_needle + 1;
  if (width > prof.needle_count)
    throw InvalidInput(fmt::format("{} needs {} needles at its widest ({}); machine '{}' has {}", what, width, counted,
                                   prof.name, prof.needle_count));
  return 1 + (prof.needle_count - width) / 2 - min_needle;
}

/// The warning for a map whose stitches use several yarns, all knitted with
/// carrier `main`; nullopt for one yarn.
inline std::optional<std::string> several_yarns_warning(const KnittingMap& map, const std::string& main) {
  std::set<int> yarns;
  for (int r = 0; r < map.rows; ++r)
    for (int c = 0; c < map.cols; ++c)
      if (is_stitch(map.at(r, c))) yarns.insert(map.yarn_at(r, c));
  if (yarns.size() <= 1) return std::nullopt;
  return fmt::format("the map uses {} yarns ({}); this program knits every stitch with carrier {}", yarns.size(),
                     fmt::join(yarns, ", "), main);
}

}  // namespace knitforge::writer_detail
