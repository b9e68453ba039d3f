#include "knitforge/machine/knitout_writer.h"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <map>
#include <set>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

char dir_char(int d) { return d > 0 ? '+' : '-'; }

class Emitter {
 public:
  Emitter(const MachineProfile& p, KnitoutStats& s) : prof_(p), stats_(s) {}

  std::string out;

  template <typename... Args>
  void line(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(out), f, std::forward<Args>(args)...);
    out.push_back('\n');
  }
  void comment(const std::string& text) { line("; {}", text); }

  void knit(int d, int n, const std::string& cs) {
    line("knit {} f{} {}", dir_char(d), n, cs);
    ++stats_.knits;
  }
  void tuck(int d, int n, const std::string& cs) {
    line("tuck {} f{} {}", dir_char(d), n, cs);
    ++stats_.tucks;
  }
  void rack(int r) {
    if (r == racking_) return;
    if (std::abs(r) > prof_.max_racking)
      throw InvalidInput(fmt::format("internal: racking {} beyond the machine limit {}", r,
                                     prof_.max_racking));
    line("rack {}", r);
    racking_ = r;
    ++stats_.racks;
  }
  void xfer_to_back(int n) {
    line("xfer f{} b{}", n, n);
    ++stats_.xfers;
  }
  void xfer_to_front(int n, int to) {
    line("xfer b{} f{}", n, to);
    ++stats_.xfers;
  }
  void carrier_in(const std::string& c) {
    line("{} {}", prof_.has_yarn_inserting_hook ? "inhook" : "in", c);
  }
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
  // Alternating tuck cast-on over lo..hi: leftwards on hi, hi-2, ...; then
  // rightwards on the others. Leaves the carrier right of hi.
  void tuck_cast_on(int lo, int hi, const std::string& c) {
    for (int n = hi; n >= lo; n -= 2) tuck(-1, n, c);
    for (int n = lo; n <= hi; ++n)
      if ((hi - n) % 2 != 0) tuck(+1, n, c);
  }

 private:
  const MachineProfile& prof_;
  KnitoutStats& stats_;
  int racking_ = 0;
};

std::string pick_carrier(const std::string& wanted, const MachineProfile& p, size_t index,
                         const char* role) {
  if (!wanted.empty()) {
    if (!p.has_carrier(wanted))
      throw InvalidInput(fmt::format("{} carrier '{}' is not a carrier of machine '{}' ({})", role,
                                     wanted, p.name, fmt::join(p.carriers, " ")));
    return wanted;
  }
  if (index >= p.carriers.size())
    throw InvalidInput(fmt::format("machine '{}' has only {} carrier(s); no {} carrier available",
                                   p.name, p.carriers.size(), role));
  return p.carriers[index];
}

}  // namespace

KnitoutProgram write_knitout(const KnittingMap& map, const MachineProfile& prof,
                             const KnitoutOptions& opt) {
  validate_machine_profile(prof);
  if (prof.beds != 2)
    throw InvalidInput(fmt::format(
        "machine '{}' has one needle bed: knitout needs a two-bed machine for transfers; "
        "use 'knitforge instructions' for hand-machine instructions",
        prof.name));
  if (opt.waste_rows < 0) throw InvalidInput("--waste-rows must be >= 0");
  if (opt.bind_off_waste_rows < 1) throw InvalidInput("bind-off waste rows must be >= 1");
  if (opt.tail_rows < 1) throw InvalidInput("bind-off tail rows must be >= 1");
  if (opt.gauge < 0) throw InvalidInput("--gauge must be positive");
  if (opt.position != "Left" && opt.position != "Center" && opt.position != "Right" &&
      opt.position != "Keep")
    throw InvalidInput(
        fmt::format("--position '{}': expected Left, Center, Right or Keep", opt.position));

  const bool need_waste = opt.waste_rows > 0 || opt.bind_off == BindOff::Waste;
  const std::string M = pick_carrier(opt.carrier, prof, 0, "main");
  std::string W, D;
  if (need_waste) {
    W = pick_carrier(opt.waste_carrier, prof, 1, "waste");
    if (W == M) throw InvalidInput(fmt::format("waste and main yarn share carrier {}", M));
  }
  if (opt.waste_rows > 0) {
    D = pick_carrier(opt.draw_carrier, prof, 2, "draw-thread");
    if (D == M || D == W)
      throw InvalidInput(fmt::format("the draw thread needs its own carrier (got {})", D));
  }

  NeedleLayoutOptions lo_opt;
  lo_opt.max_shift = prof.max_racking;
  lo_opt.max_stack = std::max(2, prof.max_transfer_stack);
  lo_opt.close_turns = opt.close_turns;
  lo_opt.max_closure_loops = 2;
  const NeedleLayout L = plan_needle_layout(map, lo_opt);

  const int width = L.max_needle - L.min_needle + 1;
  if (width > prof.needle_count)
    throw InvalidInput(fmt::format(
        "the fabric needs {} needles at its widest (including transfer steps); machine '{}' has {}",
        width, prof.name, prof.needle_count));
  const int offset = 1 + (prof.needle_count - width) / 2 - L.min_needle;
  auto N = [&](int r, int c) { return L.needle_at(r, c) + offset; };

  KnitoutProgram prog;
  KnitoutStats& st = prog.stats;
  Emitter e(prof, st);
  e.out.reserve(static_cast<size_t>(map.rows) * map.cols * 20 + 4096);

  // yarns
  {
    std::set<int> yarns;
    for (int r = 0; r < map.rows; ++r)
      for (int c = 0; c < map.cols; ++c)
        if (is_stitch(map.at(r, c))) yarns.insert(map.yarn_at(r, c));
    if (yarns.size() > 1)
      prog.warnings.push_back(fmt::format(
          "the map uses {} yarns ({}); this program knits every stitch with carrier {}",
          yarns.size(), fmt::join(yarns, ", "), M));
  }

  // 1. headers
  e.line(";!knitout-2");
  e.line(";;Machine: {}", prof.knitout_machine);
  e.line(";;Gauge: {}", opt.gauge > 0 ? opt.gauge : prof.gauge);
  if (prof.width_header) e.line(";;Width: {}", prof.needle_count);
  e.line(";;Carriers: {}", fmt::join(prof.carriers, " "));
  e.line(";;Position: {}", opt.position);
  e.comment(fmt::format("knitforge: {} x {} knitting map, {} stitches, for {} ({})", map.rows,
                        map.cols, map.num_stitches(), prof.display_name, prof.name));
  e.comment(fmt::format("main yarn carrier {}; front bed sheet knitting on needles f{}..f{}", M,
                        L.min_needle + offset, L.max_needle + offset));
  e.comment(fmt::format("limits: racking <= {}, <= {} loops per needle after a transfer",
                        prof.max_racking, lo_opt.max_stack));
  if (opt.stitch_number) e.line("x-stitch-number {}", *opt.stitch_number);
  if (opt.xfer_stitch_number) e.line("x-xfer-stitch-number {}", *opt.xfer_stitch_number);
  if (opt.speed_number) e.line("x-speed-number {}", *opt.speed_number);

  // 2. cast-on over the needles of course 0 (consecutive)
  int lo = INT32_MAX, hi = INT32_MIN;
  for (int c = 0; c < map.cols; ++c)
    if (L.alive(0, c)) {
      lo = std::min(lo, N(0, c));
      hi = std::max(hi, N(0, c));
    }
  if (opt.waste_rows > 0) {
    e.comment(fmt::format("cast-on: waste section of {} courses (carrier {}), draw thread (carrier {}), needles f{}..f{}",
                          opt.waste_rows, W, D, lo, hi));
    e.carrier_in(W);
    e.tuck_cast_on(lo, hi, W);
    e.knit_pass(-1, lo, hi, W);
    e.release(W);
    for (int i = 1; i < opt.waste_rows; ++i) e.knit_pass(i % 2 ? +1 : -1, lo, hi, W);
    e.carrier_out(W);
    e.comment("cast-on: draw thread course");
    e.carrier_in(D);
    e.knit_pass(-1, lo, hi, D);
    e.release(D);
    e.carrier_out(D);
    e.comment(fmt::format("cast-on: main yarn (carrier {}) first course", M));
    e.carrier_in(M);
    e.knit_pass(-1, lo, hi, M);
    e.release(M);
  } else {
    e.comment(fmt::format("cast-on: alternating tucks on f{}..f{} and one course (carrier {})",
                          lo, hi, M));
    e.carrier_in(M);
    e.tuck_cast_on(lo, hi, M);
    e.knit_pass(-1, lo, hi, M);
    e.release(M);
  }
  if (map.direction[0] < 0) {
    e.comment("cast-on: one more course so course 0 can start on the right");
    e.knit_pass(+1, lo, hi, M);
  }

  // 3-5. courses, turns, transfers
  for (int r = 0; r < map.rows; ++r) {
    const LayoutTransition& T = L.transitions[r];
    if (!T.steps.empty() || !T.starts.empty() || !T.merges.empty()) {
      int moves = 0;
      for (const auto& s : T.steps) moves += static_cast<int>(s.moves.size());
      std::string what;
      for (int c : T.starts)
        what += fmt::format(" increase col {} (empty f{});", c, N(r, c));
      for (const auto& m : T.merges)
        what += fmt::format(" decrease col {} onto col {} (f{});", m.col, m.onto_col,
                            N(r, m.onto_col));
      for (const auto& b : T.bind_offs) what += fmt::format(" {} col(s) bound off;", b.cols.size());
      e.comment(fmt::format("transfers before course {}:{} {} loop moves in {} step(s), pivot col {} stays on f{}",
                            r, what, moves, T.steps.size(), T.pivot_col,
                            T.pivot_needle + offset));
      int k = 0;
      for (const auto& s : T.steps) {
        ++k;
        if (s.moves.empty()) continue;
        e.comment(fmt::format("transfer step {}/{} before course {}: {} loops to the back bed and over",
                              k, T.steps.size(), r, s.moves.size()));
        e.rack(0);
        for (const auto& m : s.moves) e.xfer_to_back(m.from + offset);
        ++st.transfer_passes;
        std::map<int, std::vector<const LayoutMove*>> groups;
        for (const auto& m : s.moves) groups[m.to - m.from].push_back(&m);
        for (const auto& [d, ms] : groups) {
          e.rack(d);
          for (const auto* m : ms) e.xfer_to_front(m->from + offset, m->to + offset);
          ++st.transfer_passes;
        }
        e.rack(0);
      }
    }

    const int d = map.direction[r];
    int nst = 0;
    for (int c = L.first_col[r]; c <= L.last_col[r]; ++c)
      if (is_stitch(map.at(r, c))) ++nst;
    int held = 0;
    for (int c = 0; c < map.cols; ++c) held += L.alive(r, c) && !is_stitch(map.at(r, c));
    e.comment(fmt::format("course {}: direction {}, columns {}..{}, {} stitches, needles f{}..f{}{}", r,
                          dir_char(d), L.first_col[r], L.last_col[r], nst, N(r, L.first_col[r]),
                          N(r, L.last_col[r]),
                          held ? fmt::format(", short row ({} held loops)", held) : std::string()));
    const std::vector<int>& starts = T.starts;
    // Bind-off chains after this row's last stitches (needle_layout.h):
    // during the row, col -> the needle its bind-off loop moves to.
    static const std::vector<LayoutBindOff> kNoBindOffs;
    const std::vector<LayoutBindOff>& chains = r + 1 < map.rows ? L.transitions[r + 1].bind_offs : kNoBindOffs;
    std::map<int, int> chain_next;
    for (const auto& b : chains) {
      if (!b.during_row) continue;
      for (size_t i = 0; i < b.cols.size(); ++i)
        chain_next[b.cols[i]] = i + 1 < b.cols.size() ? b.cols[i + 1] : b.onto_col;
    }
    // A bind-off step: knit needle n once more (the loop that secures it),
    // then move that loop onto needle `to` (a neighbour).
    auto bind_off_step = [&](int dir, int n, int to, bool knit) {
      if (knit) e.knit(dir, n, M);
      e.rack(0);
      e.xfer_to_back(n);
      e.rack(to - n);
      e.xfer_to_front(n, to);
      e.rack(0);
      st.transfer_passes += 2;
    };
    auto do_cell = [&](int c) {
      if (!is_stitch(map.at(r, c))) return;
      const bool first = r > 0 && std::binary_search(starts.begin(), starts.end(), c);
      if (first) {
        e.tuck(d, N(r, c), M);
        ++st.map_tucks;
      } else {
        e.knit(d, N(r, c), M);
        ++st.map_knits;
      }
      if (const auto it = chain_next.find(c); it != chain_next.end()) {
        e.comment(fmt::format("bind-off during course {}: col {} (f{}) knitted again, its loop onto col {} (f{})",
                              r, c, N(r, c), it->second, N(r, it->second)));
        bind_off_step(d, N(r, c), N(r, it->second), true);
        e.comment(fmt::format("course {} (continued)", r));
      }
    };
    if (d > 0)
      for (int c = L.first_col[r]; c <= L.last_col[r]; ++c) do_cell(c);
    else
      for (int c = L.last_col[r]; c >= L.first_col[r]; --c) do_cell(c);
    ++st.courses;

    if (L.inside_turn[r]) {
      ++st.inside_turns;
      if (L.closure_col[r] >= 0) {
        const int h = L.closure_col[r];
        e.comment(fmt::format("turn after course {}: tuck on held needle f{} (col {}) closes the turn",
                              r, N(r, h), h));
        e.tuck(d, N(r, h), M);
        ++st.closed_turns;
      } else {
        e.comment(fmt::format("turn after course {}: left open ({})", r,
                              opt.close_turns ? "the held needle is at its loop limit"
                                              : "turn closure disabled"));
        ++st.open_turns;
      }
    }
    for (const auto& b : chains) {
      if (b.during_row) continue;
      // Back from the fabric edge (where the carrier is) towards onto_col.
      e.comment(fmt::format("bind-off after course {}: cols {}..{} (f{}..f{}) by a chain onto col {} (f{})", r,
                            b.cols.front(), b.cols.back(), N(r, b.cols.front()), N(r, b.cols.back()), b.onto_col,
                            N(r, b.onto_col)));
      for (size_t i = 0; i < b.cols.size(); ++i) {
        const int to = i + 1 < b.cols.size() ? b.cols[i + 1] : b.onto_col;
        bind_off_step(-d, N(r, b.cols[i]), N(r, to), true);
      }
    }
  }

  // 6. bind-off over the live loops after the last course
  const int last = map.rows - 1;
  lo = INT32_MAX;
  hi = INT32_MIN;
  for (int c = 0; c < map.cols; ++c)
    if (L.alive(last, c)) {
      lo = std::min(lo, N(last, c));
      hi = std::max(hi, N(last, c));
    }
  if (opt.bind_off == BindOff::Chain) {
    const int dl = map.direction[last];
    const int end_needle = dl > 0 ? N(last, L.last_col[last]) : N(last, L.first_col[last]);
    // carrier sits just beyond end_needle in direction dl
    const int to_hi = dl > 0 ? hi - end_needle : hi - end_needle + 1;
    const int to_lo = dl > 0 ? end_needle - lo + 1 : end_needle - lo;
    int bd;  // bind-off direction
    if (to_hi <= to_lo) {
      bd = -1;
      if (!(dl > 0 && end_needle == hi)) {
        if (to_hi > prof.max_float_needles)
          throw InvalidInput(fmt::format(
              "chain bind-off: the carrier would float {} needles to the end of the last course; "
              "the machine allows {}; use --bind-off waste",
              to_hi, prof.max_float_needles));
        e.comment("bind-off: carrier moves over the held loops to the right end");
        e.line("miss + f{} {}", hi, M);
      }
    } else {
      bd = +1;
      if (!(dl < 0 && end_needle == lo)) {
        if (to_lo > prof.max_float_needles)
          throw InvalidInput(fmt::format(
              "chain bind-off: the carrier would float {} needles to the end of the last course; "
              "the machine allows {}; use --bind-off waste",
              to_lo, prof.max_float_needles));
        e.comment("bind-off: carrier moves over the held loops to the left end");
        e.line("miss - f{} {}", lo, M);
      }
    }
    const int start = bd < 0 ? hi : lo, stop = bd < 0 ? lo : hi;
    e.comment(fmt::format("bind-off: chain from f{} to f{} (each loop onto the next needle, knit)",
                          start, stop));
    for (int n = start; n != stop; n += bd) {
      e.rack(0);
      e.xfer_to_back(n);
      e.rack(bd);
      e.xfer_to_front(n, n + bd);
      e.rack(0);
      st.transfer_passes += 2;
      e.knit(bd, n + bd, M);
    }
    e.comment(fmt::format("bind-off: tail of {} courses on f{}; thread the cut yarn end through its last loop",
                          opt.tail_rows, stop));
    for (int t = 0; t < opt.tail_rows; ++t) e.knit(t % 2 == 0 ? -bd : bd, stop, M);
    e.carrier_out(M);
    e.line("drop f{}", stop);
  } else {
    e.comment(fmt::format("bind-off: live loops f{}..f{} onto {} courses of waste yarn (carrier {})",
                          lo, hi, opt.bind_off_waste_rows, W));
    e.carrier_out(M);
    e.carrier_in(W);
    e.knit_pass(-1, lo, hi, W);
    e.release(W);
    for (int i = 1; i < opt.bind_off_waste_rows; ++i) e.knit_pass(i % 2 ? +1 : -1, lo, hi, W);
    e.carrier_out(W);
    e.comment("bind-off: drop the waste loops");
    for (int n = lo; n <= hi; ++n) e.line("drop f{}", n);
  }

  st.increases = L.increases;
  st.decreases = L.decreases;
  st.bound_off = L.bound_off;
  st.first_needle = L.min_needle + offset;
  st.last_needle = L.max_needle + offset;
  prog.text = std::move(e.out);
  return prog;
}

}  // namespace knitforge
