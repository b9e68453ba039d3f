#include "knitforge/machine/knitout_tube_writer.h"

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <map>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/machine/knitout_emitter.h"
#include "knitforge/machine/tube_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using writer_detail::dir_char;
using writer_detail::Emitter;

KnitoutProgram write_tube_knitout(const KnittingMap& map, const MachineProfile& prof, const KnitoutOptions& opt,
                                  const TubeWriterSetup& setup) {
  TubeLayoutOptions lo;
  lo.max_racking = prof.max_racking;
  lo.max_stack = std::max(2, prof.max_transfer_stack);
  lo.close_turns = opt.close_turns;
  lo.max_closure_loops = 2;
  const TubeLayout L = plan_tube_layout(map, lo);
  writer_detail::refuse_layout_problems(prof, L.problems, "tube");
  const int offset = writer_detail::centred_needle_offset(
      prof, L.min_needle, L.max_needle, "the tube", "every other needle on each bed, including transfer steps");
  const int R = map.rows, C = map.cols, h = map.tube_half();
  auto N = [&](int r, int c) { return L.needle_at(r, c) + offset; };
  auto back = [&](int c) { return c >= h; };
  // the carriage direction of a stitch of wale c in a row going d
  auto mdir = [&](int c, int d) { return back(c) ? -d : d; };
  const int first_dir = prof.carrier_park_side == BedSide::Left ? +1 : -1;
  // Carriers come in at the fold where a round going +1 (column order)
  // starts with a pass away from the parking side.
  const int line0 = first_dir > 0 ? 0 : h;
  const std::string& M = setup.main_carrier;
  const std::string& W = setup.waste_carrier;
  const std::string& D = setup.draw_carrier;

  KnitoutProgram prog;
  KnitoutStats& st = prog.stats;
  st.waste_rows = setup.waste_rows;
  Emitter e(prof, st);
  e.out.reserve(static_cast<size_t>(R) * C * 20 + static_cast<size_t>(setup.waste_rows) * 2000 + 4096);
  if (auto w = writer_detail::several_yarns_warning(map, M)) prog.warnings.push_back(*w);

  e.headers(opt);
  e.comment(fmt::format("knitforge: {} x {} tubular knitting map, {} stitches, for {} ({})", R, C,
                        map.num_stitches(), prof.display_name, prof.name));
  e.comment(fmt::format("main yarn carrier {}; tube knitted in the round: columns 0..{} on the front bed, {}..{} on "
                        "the back bed, every other needle (f{}..f{}, b{}..b{})",
                        M, h - 1, h, C - 1, L.min_needle + offset, L.max_needle + offset, L.min_needle + offset,
                        L.max_needle + offset));
  e.comment(fmt::format("limits: racking <= {}, <= {} loops per needle after a transfer", prof.max_racking,
                        lo.max_stack));

  // The alive wales of row r once round from seam line `line` going d.
  auto round_from = [&](int r, int line, int d) {
    std::vector<int> out;
    for (int k = 0; k < C; ++k) {
      const int c = d > 0 ? (line + k) % C : ((line - 1 - k) % C + C) % C;
      if (L.alive(r, c)) out.push_back(c);
    }
    return out;
  };
  const std::vector<int> ring0 = round_from(0, line0, +1);
  auto tuck_rounds = [&](const std::string& cs) {
    for (int parity : {0, 1})
      for (size_t i = static_cast<size_t>(parity); i < ring0.size(); i += 2)
        e.tuck_on(mdir(ring0[i], +1), back(ring0[i]), N(0, ring0[i]), cs);
  };
  auto knit_round = [&](int r, const std::vector<int>& ring, int d, const std::string& cs) {
    for (int c : ring) e.knit_on(mdir(c, d), back(c), N(r, c), cs);
  };

  // 2. waste and cast-on
  if (setup.waste_rows > 0) {
    e.comment(fmt::format("waste: {} rounds (carrier {}), then a draw thread (carrier {}) round the tube; {}",
                          setup.waste_rows, W, D, prof.writer.waste_reason));
    e.settings(prof.writer.waste);
    e.carrier_in(W);
    tuck_rounds(W);
    knit_round(0, ring0, +1, W);
    e.release(W);
    for (int i = 1; i < setup.waste_rows; ++i) knit_round(0, ring0, +1, W);
    e.carrier_out(W);
    e.comment("draw-thread: one round, pulled out later to take the waste off");
    e.carrier_in(D);
    knit_round(0, ring0, +1, D);
    e.release(D);
    e.carrier_out(D);
    e.comment(fmt::format("cast-on: main yarn (carrier {}) first round over the draw thread", M));
    e.settings(prof.writer.cast_on);
    e.carrier_in(M);
    knit_round(0, ring0, +1, M);
    e.release(M);
  } else {
    e.comment(fmt::format("cast-on: tucks on every other wale round the tube, then the others, and one round "
                          "(carrier {})",
                          M));
    e.settings(prof.writer.cast_on);
    e.carrier_in(M);
    tuck_rounds(M);
    knit_round(0, ring0, +1, M);
    e.release(M);
  }
  // Course 0 starts at its seam, in its direction: the cast-on goes on to it.
  {
    const int d0 = map.direction[0];
    int first = -1;
    for (int c : row_columns(map, 0))
      if (is_stitch(map.at(0, c))) {
        first = c;
        break;
      }
    // the carrier sits at line0 having gone round +1; it goes on (or turns
    // back, for a course 0 going -1) from there
    std::vector<int> more;
    for (int c : round_from(0, line0, d0)) {
      if (c == first) break;
      more.push_back(c);
    }
    if (!more.empty()) {
      e.comment(fmt::format("cast-on: {} more stitches round to the seam of course 0", more.size()));
      knit_round(0, more, d0, M);
    }
  }
  e.settings(setup.body);

  // 3-4. courses, turns, transfers
  e.fabric = true;
  for (int r = 0; r < R; ++r) {
    const TubeTransition& T = L.transitions[static_cast<size_t>(r)];
    if (!T.steps.empty() || !T.starts.empty() || !T.merges.empty()) {
      std::string what;
      for (int c : T.starts) what += fmt::format(" increase col {} (empty {}{});", c, back(c) ? 'b' : 'f', N(r, c));
      for (const auto& m : T.merges)
        what += fmt::format(" decrease col {} onto col {} ({}{});", m.col, m.onto_col, back(m.onto_col) ? 'b' : 'f',
                            N(r, m.onto_col));
      int moves = 0;
      for (const auto& s : T.steps) moves += static_cast<int>(s.size());
      e.comment(fmt::format("transfers before course {}:{} {} loop moves in {} step(s)", r, what, moves,
                            T.steps.size()));
      int k = 0;
      for (const auto& s : T.steps) {
        ++k;
        if (s.empty()) continue;
        e.comment(fmt::format("transfer step {}/{} before course {}: {} loops to the other bed and over", k,
                              T.steps.size(), r, s.size()));
        e.rack(0);
        for (const auto& m : s) e.xfer(m.back, m.from + offset, m.from + offset);
        ++st.transfer_passes;
        // back bed needle n faces front needle n + racking
        std::map<int, std::vector<const TubeMove*>> groups;
        for (const auto& m : s) groups[m.back ? m.from - m.to : m.to - m.from].push_back(&m);
        for (const auto& [rk, ms] : groups) {
          e.rack(rk);
          for (const TubeMove* m : ms) e.xfer(!m->back, m->from + offset, m->to + offset);
          ++st.transfer_passes;
        }
        e.rack(0);
      }
    }

    const int d = map.direction[static_cast<size_t>(r)];
    int nst = 0;
    for (int c = 0; c < C; ++c) nst += is_stitch(map.at(r, c));
    e.comment(fmt::format("course {}: {}, direction {}, {} stitches{}", r,
                          map.closed(r) ? fmt::format("round from seam {}", map.seam[static_cast<size_t>(r)])
                                        : std::string("short row"),
                          dir_char(d), nst, map.closed(r) ? std::string() : std::string(" (other wales held)")));
    for (int c : row_columns(map, r)) {
      if (!is_stitch(map.at(r, c))) continue;
      const bool first = r > 0 && std::binary_search(T.starts.begin(), T.starts.end(), c);
      if (first) {
        e.tuck_on(mdir(c, d), back(c), N(r, c), M);
        ++st.map_tucks;
      } else {
        e.knit_on(mdir(c, d), back(c), N(r, c), M);
        ++st.map_knits;
      }
    }
    ++st.courses;
    if (L.inside_turn[static_cast<size_t>(r)]) {
      ++st.inside_turns;
      const int hc = L.closure_col[static_cast<size_t>(r)];
      if (hc >= 0) {
        e.comment(fmt::format("turn after course {}: tuck on held needle {}{} (col {}) closes the turn", r,
                              back(hc) ? 'b' : 'f', N(r, hc), hc));
        e.tuck_on(mdir(hc, d), back(hc), N(r, hc), M);
        ++st.closed_turns;
      } else {
        e.comment(fmt::format("turn after course {}: left open", r));
        ++st.open_turns;
      }
    }
  }
  e.fabric = false;

  // Moves one loop from (from_back, from) to (to_back, to) during the
  // bind-off, when every loop rests on its wale's needle: front wales on
  // needles of one parity, back wales on the other, so the front needles of
  // the back wales' parity and the back needles of the front wales' parity
  // are empty. Within the racking limit it is one transfer (to the other
  // bed) or two (there and back, racked); further, the loop walks over
  // those empty needles, a bed change per transfer, each within the limit.
  // A walk is announced by a `; bind-off: ... walks to ...` comment.
  // Returns the transfer passes.
  const int max_rack = prof.max_racking;
  auto parity = [](int n) { return (n % 2 + 2) % 2; };
  const int front_parity = [&] {
    for (int c = 0; c < h; ++c)
      if (is_stitch(map.at(R - 1, c))) return parity(N(R - 1, c));
    return 0;
  }();
  auto move_loop = [&](bool from_back, int from, bool to_back, int to) {
    bool cur_back = from_back;
    int cur = from, passes = 0;
    auto hop = [&](bool next_back, int next) {
      e.rack(cur_back ? next - cur : cur - next);  // back needle n faces front needle n + racking
      e.xfer(cur_back, cur, next);
      ++passes;
      cur_back = next_back;
      cur = next;
    };
    if (from_back == to_back && std::abs(to - from) <= max_rack) {
      hop(!from_back, from);  // straight across, then back racked
      hop(to_back, to);
      return passes;
    }
    if (!(from_back != to_back && std::abs(to - from) <= max_rack))
      e.comment(fmt::format("bind-off: {}{} walks to {}{} ({} needles, racking <= {})", from_back ? 'b' : 'f', from,
                            to_back ? 'b' : 'f', to, std::abs(to - from), max_rack));
    while (!(cur_back != to_back && std::abs(to - cur) <= max_rack)) {
      if (max_rack < 1)
        throw InvalidInput(fmt::format("tube bind-off: moving the loop of {}{} onto {}{} needs racking; machine '{}' "
                                       "does not rack; use --bind-off waste",
                                       from_back ? 'b' : 'f', from, to_back ? 'b' : 'f', to, prof.name));
      const bool next_back = !cur_back;
      const int empty_parity = next_back ? front_parity : 1 - front_parity;  // an empty needle there
      const int d = to >= cur ? 1 : -1;
      int k = std::min(max_rack, std::abs(to - cur));
      if (parity(cur + d * k) != empty_parity) --k;
      if (k <= 0) k = parity(cur + d) == empty_parity ? 1 : 2;  // beside the target: step over it
      if (k > max_rack)
        throw InvalidInput(fmt::format("tube bind-off: moving the loop of {}{} onto {}{} needs racking {}; machine "
                                       "'{}' racks at most {}; use --bind-off waste",
                                       from_back ? 'b' : 'f', from, to_back ? 'b' : 'f', to, k, prof.name, max_rack));
      hop(next_back, cur + d * k);
    }
    hop(to_back, to);
    return passes;
  };

  // 5. bind-off
  const int last = R - 1;
  const int dl = map.direction[static_cast<size_t>(last)];
  // A loop the chain bind-off passes: its bed, needle and the carriage
  // direction it is knitted in.
  struct Spot {
    bool back;
    int needle, dir;
  };
  std::vector<Spot> chain;  // in bind-off order
  if (map.closed_end) {
    // Closing seam: each back loop onto the front needle of its pair, one
    // joining pass over the front needles (each knits through its pair), then
    // the joined loops chain off along the front bed.
    const auto pairs = closing_pairs(map);
    if (pairs.empty())
      throw InvalidInput(fmt::format("tube knitout: the tube is closed after its last round ({}), whose halves hold "
                                     "different numbers of stitches; no closing seam can pair them",
                                     last));
    std::map<int, std::vector<std::pair<int, int>>> by_racking;  // racking -> {back needle, front needle}
    std::vector<std::pair<int, int>> far;  // pairs further apart than the machine racks
    for (const auto& [f, b] : pairs) {
      const int nf = N(last, f), nb = N(last, b);
      (std::abs(nf - nb) <= max_rack ? by_racking[nf - nb] : far).emplace_back(nb, nf);
    }
    e.comment(fmt::format("bind-off: closing seam, {} back loops onto the front needles of their pairs", pairs.size()));
    e.settings(prof.writer.bind_off);
    for (const auto& [rk, moves] : by_racking) {
      e.rack(rk);
      for (const auto& [nb, nf] : moves) e.xfer(true, nb, nf);
      ++st.transfer_passes;
    }
    // a pair further apart than the racking limit: the back loop walks over
    for (const auto& [nb, nf] : far) st.transfer_passes += move_loop(true, nb, false, nf);
    e.rack(0);
    // The carrier stands where the last round ended (its seam); it goes to
    // the nearer end of the front bed and joins from there.
    const int seam_line = map.seam[static_cast<size_t>(last)];
    const int lo = N(last, pairs.front().first), hi = N(last, pairs.back().first);
    const bool from_left = seam_line == 0 || (seam_line != h && (seam_line < h ? seam_line <= h / 2
                                                                               : C - seam_line <= (C - h) / 2));
    const int dj = from_left ? +1 : -1;
    if (seam_line != 0 && seam_line != h) {
      // the carrier is inside a bed: bring it to the joining pass's start
      e.comment(fmt::format("bind-off: carrier {} moves to the {} end of the front bed", M,
                            from_left ? "left" : "right"));
      e.miss_on(-dj, false, from_left ? lo : hi, M);
    }
    e.comment(fmt::format("bind-off: joining pass, {} front needles each knit through their two loops", pairs.size()));
    for (size_t k = 0; k < pairs.size(); ++k)
      e.knit_on(dj, false, N(last, pairs[from_left ? k : pairs.size() - 1 - k].first), M);
    for (size_t k = 0; k < pairs.size(); ++k)
      chain.push_back({false, N(last, pairs[from_left ? pairs.size() - 1 - k : k].first), -dj});
    e.comment(fmt::format("bind-off: chain along the joined front loops from f{}, {} loops", from_left ? hi : lo,
                          chain.size()));
  } else {
    for (int c : row_columns(map, last))
      if (is_stitch(map.at(last, c))) chain.push_back({back(c), N(last, c), mdir(c, dl)});
  }
  if (opt.bind_off == BindOff::Chain || map.closed_end) {
    if (!map.closed_end) {
      e.comment(fmt::format("bind-off: chain round the tube from the seam (each loop onto the next wale's needle, "
                            "knit), {} loops",
                            chain.size()));
      e.settings(prof.writer.bind_off);
    }
    for (size_t k = 0; k + 1 < chain.size(); ++k) {
      const Spot a = chain[k], b = chain[k + 1];
      // within a bed: to the other bed and back racked; across a fold: one
      // transfer; beyond the racking limit: walked over empty needles
      st.transfer_passes += move_loop(a.back, a.needle, b.back, b.needle);
      e.rack(0);
      e.knit_on(b.dir, b.back, b.needle, M);
    }
    const Spot stop = chain.back();
    const int ns = stop.needle, bd = stop.dir;
    e.comment(fmt::format("bind-off: tail of {} stitches on {}{}; thread the cut yarn end through its last loop",
                          opt.tail_rows, stop.back ? 'b' : 'f', ns));
    for (int t = 0; t < opt.tail_rows; ++t) e.knit_on(t % 2 == 0 ? -bd : bd, stop.back, ns, M);
    const int beyond = ns + 2 * bd;
    if (beyond >= 1 && beyond <= prof.needle_count) {
      e.comment(fmt::format("bind-off: carrier {} moves two needles on before it goes out", M));
      e.miss_on(bd, stop.back, beyond, M);
    }
    e.carrier_out(M);
    e.line("drop {}{}", stop.back ? 'b' : 'f', ns);
  } else {
    e.comment(fmt::format("bind-off: live loops onto {} rounds of waste yarn (carrier {})", opt.bind_off_waste_rows,
                          W));
    e.carrier_out(M);
    e.settings(prof.writer.waste);
    e.carrier_in(W);
    const std::vector<int> ringw = round_from(last, line0, +1);
    knit_round(last, ringw, +1, W);
    e.release(W);
    for (int i = 1; i < opt.bind_off_waste_rows; ++i) knit_round(last, ringw, +1, W);
    e.carrier_out(W);
    e.comment("bind-off: drop the waste loops");
    for (int c : ringw) e.line("drop {}{}", back(c) ? 'b' : 'f', N(last, c));
  }

  prog.main_carrier = M;
  prog.waste_carrier = W;
  prog.draw_carrier = D;
  st.increases = L.increases;
  st.decreases = L.decreases;
  st.first_needle = L.min_needle + offset;
  st.last_needle = L.max_needle + offset;
  prog.text = std::move(e.out);
  return prog;
}

}  // namespace knitforge
