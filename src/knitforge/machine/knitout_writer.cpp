#include "knitforge/machine/knitout_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <map>
#include <set>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/convert/map_knittability.h"
#include "knitforge/machine/knitout_emitter.h"
#include "knitforge/machine/knitout_extensions.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_tube_writer.h"
#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

using writer_detail::dir_char;
using writer_detail::Emitter;
using writer_detail::several_yarns_warning;

std::string pick_carrier(const std::string& wanted, const MachineProfile& p, size_t index, const char* role) {
  if (!wanted.empty()) {
    if (!p.has_carrier(wanted))
      throw InvalidInput(fmt::format("{} carrier '{}' is not a carrier of machine '{}' ({})", role, wanted, p.name,
                                     fmt::join(p.carriers, " ")));
    return wanted;
  }
  if (index >= p.carriers.size())
    throw InvalidInput(fmt::format("machine '{}' has only {} carrier(s); no {} carrier available", p.name,
                                   p.carriers.size(), role));
  return p.carriers[index];
}

// The fabric settings: the profile's, with the fields the options set.
SectionSettings body_settings(const MachineProfile& p, const SectionSettings& o) {
  SectionSettings s = p.writer.body;
  if (!o.stitch_number.empty()) s.stitch_number = o.stitch_number;
  if (!o.xfer_stitch_number.empty()) s.xfer_stitch_number = o.xfer_stitch_number;
  if (o.speed_number >= 0) s.speed_number = o.speed_number;
  if (o.roller_advance >= 0) s.roller_advance = o.roller_advance;
  return s;
}

// Refuses settings the machine's software does not read or accept.
void check_settings(const MachineProfile& p, const SectionSettings& s) {
  auto check = [&](const char* ext, const std::string& value) {
    if (value.empty()) return;
    const ExtensionRule* rule = p.extension(ext);
    if (!rule)
      throw InvalidInput(fmt::format("machine '{}' does not read {} (its translator ignores it)", p.name, ext));
    const std::string problem = extension_value_problem(*rule, {value});
    if (!problem.empty()) throw InvalidInput(fmt::format("machine '{}': {}", p.name, problem));
  };
  check("x-stitch-number", s.stitch_number);
  check("x-xfer-stitch-number", s.xfer_stitch_number);
  check("x-speed-number", s.speed_number >= 0 ? std::to_string(s.speed_number) : std::string());
  check("x-roller-advance", s.roller_advance >= 0 ? std::to_string(s.roller_advance) : std::string());
}

// The first error of a knittability report, for a one-line message.
std::string first_violation(const KnittabilityReport& r) {
  for (const auto& v : r.violations) {
    if (v.severity == Severity::Error) return fmt::format("[{}] {}", rule_id(v.rule), v.message);
  }
  return "(no listed violation)";
}

}  // namespace

KnitoutProgram write_knitout(const KnittingMap& map, const MachineProfile& prof, const KnitoutOptions& opt) {
  validate_machine_profile(prof);
  if (prof.beds != 2)
    throw InvalidInput(fmt::format(
        "machine '{}' has one needle bed: knitout needs a two-bed machine for transfers; "
        "use 'knitforge instructions' for hand-machine instructions",
        prof.name));
  const int waste_rows = opt.waste_rows < 0 ? prof.writer.waste_rows : opt.waste_rows;
  if (opt.waste_rows < -1 || waste_rows > kMaxWasteRows)
    throw InvalidInput(fmt::format("--waste-rows {}: expected 0..{} courses (-1: the machine's default)",
                                   opt.waste_rows, kMaxWasteRows));
  if (opt.bind_off_waste_rows < 1 || opt.bind_off_waste_rows > kMaxWasteRows)
    throw InvalidInput(fmt::format("bind-off waste rows {}: expected 1..{}", opt.bind_off_waste_rows, kMaxWasteRows));
  if (opt.tail_rows < 1 || opt.tail_rows > 100)
    throw InvalidInput(fmt::format("bind-off tail rows {}: expected 1..100", opt.tail_rows));
  if (!(opt.gauge >= 0) || !std::isfinite(opt.gauge))
    throw InvalidInput(fmt::format("--gauge {}: expected a positive number", opt.gauge));
  if (opt.position != "Left" && opt.position != "Center" && opt.position != "Right" && opt.position != "Keep")
    throw InvalidInput(fmt::format("--position '{}': expected Left, Center, Right or Keep", opt.position));
  const SectionSettings body = body_settings(prof, opt.body);
  check_settings(prof, body);

  const bool need_waste = waste_rows > 0 || opt.bind_off == BindOff::Waste;
  const std::string M = pick_carrier(opt.carrier, prof, 0, "main");
  std::string W, D;
  if (need_waste) {
    W = pick_carrier(opt.waste_carrier, prof, 1, "waste");
    if (W == M) throw InvalidInput(fmt::format("waste and main yarn share carrier {}", M));
  }
  if (waste_rows > 0) {
    D = pick_carrier(opt.draw_carrier, prof, 2, "draw-thread");
    if (D == M || D == W) throw InvalidInput(fmt::format("the draw thread needs its own carrier (got {})", D));
  }

  const KnittabilityReport check = check_knittability(map);
  if (!check.ok())
    throw InvalidInput(fmt::format("the knitting map is not knittable ({} error(s)): {}; run 'knitforge check' for "
                                   "the full list",
                                   check.num_errors(), first_violation(check)));

  // The self-check of every program (see the file comment).
  auto verified = [&](KnitoutProgram prog) {
    if (!opt.verify) return prog;
    SimulateOptions so;
    so.strict = all_rules_strict();
    // a ;;Gauge: the user chose is a warning the program keeps
    if (opt.gauge > 0 && opt.gauge != prof.gauge) so.strict[static_cast<size_t>(KnitoutRule::Header)] = false;
    KnitoutSimulation sim = simulate_knitout(parse_knitout(prog.text), prof, so);
    GraphComparison cmp = compare_knit_graph(sim.graph, map);
    if (!sim.ok() || !cmp.ok()) {
      std::string why;
      for (const auto& dg : sim.diagnostics) {
        if (dg.severity == Severity::Error) {
          why = fmt::format("line {}: [{}] {}", dg.line, knitout_check_id(dg.check), dg.message);
          break;
        }
      }
      if (why.empty() && !cmp.issues.empty()) why = cmp.issues.front().message;
      throw Error(fmt::format("knitforge wrote a program for machine '{}' that its own simulator rejects ({} error(s), "
                              "{} mismatch(es) with the map): {}; this is a knitforge bug: please report it with the "
                              "map",
                              prof.name, sim.errors, cmp.mismatches, why));
    }
    prog.simulation = std::move(sim);
    prog.comparison = std::move(cmp);
    return prog;
  };
  if (map.tubular()) {
    TubeWriterSetup setup;
    setup.main_carrier = M;
    setup.waste_carrier = W;
    setup.draw_carrier = D;
    setup.waste_rows = waste_rows;
    setup.body = body;
    return verified(write_tube_knitout(map, prof, opt, setup));
  }

  NeedleLayoutOptions lo_opt;
  lo_opt.max_shift = prof.max_racking;
  lo_opt.max_stack = std::max(2, prof.max_transfer_stack);
  lo_opt.close_turns = opt.close_turns;
  lo_opt.max_closure_loops = 2;
  const NeedleLayout L = plan_needle_layout(map, lo_opt);
  writer_detail::refuse_layout_problems(prof, L.problems, "map");

  const int offset = writer_detail::centred_needle_offset(prof, L.min_needle, L.max_needle, "the fabric",
                                                          "including transfer steps");
  auto N = [&](int r, int c) { return L.needle_at(r, c) + offset; };
  // the direction of a carrier's first pass after `in`
  const int first_dir = prof.carrier_park_side == BedSide::Left ? +1 : -1;

  KnitoutProgram prog;
  KnitoutStats& st = prog.stats;
  st.waste_rows = waste_rows;
  Emitter e(prof, st);
  e.out.reserve(static_cast<size_t>(map.rows) * map.cols * 20 + static_cast<size_t>(waste_rows) * 2000 + 4096);

  // yarns
  if (auto w = several_yarns_warning(map, M)) prog.warnings.push_back(*w);

  // 1. headers
  e.headers(opt);
  e.comment(fmt::format("knitforge: {} x {} knitting map, {} stitches, for {} ({})", map.rows, map.cols,
                        map.num_stitches(), prof.display_name, prof.name));
  e.comment(fmt::format("main yarn carrier {}; front bed sheet knitting on needles f{}..f{}", M, L.min_needle + offset,
                        L.max_needle + offset));
  e.comment(fmt::format("limits: racking <= {}, <= {} loops per needle after a transfer", prof.max_racking,
                        lo_opt.max_stack));

  // 2. waste section and cast-on over the needles of course 0 (consecutive)
  int lo = INT32_MAX, hi = INT32_MIN;
  for (int c = 0; c < map.cols; ++c)
    if (L.alive(0, c)) {
      lo = std::min(lo, N(0, c));
      hi = std::max(hi, N(0, c));
    }
  int carrier_dir;  // direction of the main carrier's last pass
  if (waste_rows > 0) {
    e.comment(fmt::format("waste: {} courses (carrier {}), then a draw thread (carrier {}), needles f{}..f{}; {}",
                          waste_rows, W, D, lo, hi, prof.writer.waste_reason));
    e.settings(prof.writer.waste);
    e.carrier_in(W);
    e.tuck_cast_on(first_dir, lo, hi, W);
    e.knit_pass(first_dir, lo, hi, W);
    e.release(W);
    for (int i = 1; i < waste_rows; ++i) e.knit_pass(i % 2 ? -first_dir : first_dir, lo, hi, W);
    e.carrier_out(W);
    e.comment("draw-thread: one course, pulled out later to take the waste off");
    e.carrier_in(D);
    e.knit_pass(first_dir, lo, hi, D);
    e.release(D);
    e.carrier_out(D);
    e.comment(fmt::format("cast-on: main yarn (carrier {}) first course over the draw thread", M));
    e.settings(prof.writer.cast_on);
    e.carrier_in(M);
    e.knit_pass(first_dir, lo, hi, M);
    e.release(M);
    carrier_dir = first_dir;
  } else {
    e.comment(fmt::format("cast-on: alternating tucks on f{}..f{} and one course (carrier {})", lo, hi, M));
    e.settings(prof.writer.cast_on);
    e.carrier_in(M);
    e.tuck_cast_on(first_dir, lo, hi, M);
    e.knit_pass(first_dir, lo, hi, M);
    e.release(M);
    carrier_dir = first_dir;
  }
  // The carrier is at the far end of its last pass; course 0 starts there
  // only when it runs back.
  if (map.direction[0] == carrier_dir) {
    e.comment("cast-on: one more course so course 0 can start on its side");
    e.knit_pass(-carrier_dir, lo, hi, M);
  }
  e.settings(body);


  // 3-5. courses, turns, transfers
  e.fabric = true;
  for (int r = 0; r < map.rows; ++r) {
    const LayoutTransition& T = L.transitions[r];
    if (!T.steps.empty() || !T.starts.empty() || !T.merges.empty()) {
      int moves = 0;
      for (const auto& s : T.steps) moves += static_cast<int>(s.moves.size());
      std::string what;
      for (int c : T.starts) what += fmt::format(" increase col {} (empty f{});", c, N(r, c));
      for (const auto& m : T.merges)
        what += fmt::format(" decrease col {} onto col {} (f{});", m.col, m.onto_col, N(r, m.onto_col));
      e.comment(fmt::format("transfers before course {}:{} {} loop moves in {} step(s), pivot col {} stays on f{}", r,
                            what, moves, T.steps.size(), T.pivot_col, T.pivot_needle + offset));
      int k = 0;
      for (const auto& s : T.steps) {
        ++k;
        if (s.moves.empty()) continue;
        e.comment(fmt::format("transfer step {}/{} before course {}: {} loops to the back bed and over", k,
                              T.steps.size(), r, s.moves.size()));
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
    e.comment(fmt::format("course {}: direction {}, columns {}..{}, {} stitches, needles f{}..f{}{}", r, dir_char(d),
                          L.first_col[r], L.last_col[r], nst, N(r, L.first_col[r]), N(r, L.last_col[r]),
                          held ? fmt::format(", short row ({} held loops)", held) : std::string()));
    std::vector<const LayoutChain*> in_chains;
    for (const auto& ch : L.chains)
      if (ch.row == r) in_chains.push_back(&ch);
    for (const LayoutChain* ch : in_chains)
      e.comment(fmt::format("bound off along course {}: columns {} each knitted, then moved onto the next needle "
                            "(knit, pass over), ending on col {}",
                            r, fmt::join(ch->cols, " "), ch->onto_col));
    const std::vector<int>& starts = T.starts;
    bool chain_loop_here = false;  // the previous stitch's loop was passed over onto this needle
    auto do_cell = [&](int c) {
      if (!is_stitch(map.at(r, c))) return;
      // a wale's first stitch is a tuck on its empty needle, unless a chain
      // loop was passed onto it
      const bool first = r > 0 && std::binary_search(starts.begin(), starts.end(), c) && !chain_loop_here;
      if (first) {
        e.tuck(d, N(r, c), M);
        ++st.map_tucks;
      } else {
        e.knit(d, N(r, c), M);
        ++st.map_knits;
      }
      chain_loop_here = false;
      for (const LayoutChain* ch : in_chains) {
        if (std::find(ch->cols.begin(), ch->cols.end(), c) != ch->cols.end()) {
          e.move_loops(N(r, c), d);
          chain_loop_here = true;
        }
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
        e.comment(fmt::format("turn after course {}: tuck on held needle f{} (col {}) closes the turn", r, N(r, h), h));
        e.tuck(d, N(r, h), M);
        ++st.closed_turns;
      } else {
        e.comment(fmt::format("turn after course {}: left open ({})", r,
                              opt.close_turns ? "the held needle is at its loop limit" : "turn closure disabled"));
        ++st.open_turns;
      }
    }
  }
  e.fabric = false;

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
    // carrier sits just beyond end_needle in direction dl; the float to the
    // start of a chain running in direction bd
    auto float_to_start = [&](int bd) { return bd < 0 ? (dl > 0 ? hi - end_needle : hi - end_needle + 1)
                                                      : (dl > 0 ? end_needle - lo + 1 : end_needle - lo); };
    auto at_start = [&](int bd) { return bd < 0 ? (dl > 0 && end_needle == hi) : (dl < 0 && end_needle == lo); };
    auto possible = [&](int bd) { return at_start(bd) || float_to_start(bd) <= prof.max_float_needles; };
    // prefer the chain that ends on the carriers' parking side, else the
    // shorter float
    int bd = float_to_start(-1) <= float_to_start(+1) ? -1 : +1;
    const int park = prof.carrier_park_side == BedSide::Left ? -1 : prof.carrier_park_side == BedSide::Right ? +1 : 0;
    if (park != 0 && possible(park)) bd = park;
    if (!possible(bd))
      throw InvalidInput(fmt::format(
          "chain bind-off: the carrier would float {} needles to the end of the last course; the machine allows {}; "
          "use --bind-off waste",
          float_to_start(bd), prof.max_float_needles));
    e.comment(fmt::format("bind-off: chain from f{} to f{} (each loop onto the next needle, knit)",
                          bd < 0 ? hi : lo, bd < 0 ? lo : hi));
    e.settings(prof.writer.bind_off);
    if (!at_start(bd)) {
      e.comment(fmt::format("bind-off: carrier moves over the held loops to the {} end", bd < 0 ? "right" : "left"));
      e.miss(-bd, bd < 0 ? hi : lo, M);
    }
    const int start = bd < 0 ? hi : lo, stop = bd < 0 ? lo : hi;
    for (int n = start; n != stop; n += bd) {
      e.move_loops(n, bd);
      e.knit(bd, n + bd, M);
    }
    e.comment(fmt::format("bind-off: tail of {} courses on f{}; thread the cut yarn end through its last loop",
                          opt.tail_rows, stop));
    for (int t = 0; t < opt.tail_rows; ++t) e.knit(t % 2 == 0 ? -bd : bd, stop, M);
    // The chain ended at a fabric edge (stop); the carrier moves two needles
    // beyond it, out of the way of the take-down, before it goes out.
    const int beyond = stop + 2 * bd;
    if (beyond >= 1 && beyond <= prof.needle_count) {
      e.comment(fmt::format("bind-off: carrier {} moves beyond the fabric edge (f{}) before it goes out", M, beyond));
      e.miss(bd, beyond, M);
    }
    e.carrier_out(M);
    e.line("drop f{}", stop);
  } else {
    e.comment(fmt::format("bind-off: live loops f{}..f{} onto {} courses of waste yarn (carrier {})", lo, hi,
                          opt.bind_off_waste_rows, W));
    e.carrier_out(M);
    e.settings(prof.writer.waste);
    e.carrier_in(W);
    e.knit_pass(first_dir, lo, hi, W);
    e.release(W);
    for (int i = 1; i < opt.bind_off_waste_rows; ++i) e.knit_pass(i % 2 ? -first_dir : first_dir, lo, hi, W);
    e.carrier_out(W);
    e.comment("bind-off: drop the waste loops");
    for (int n = lo; n <= hi; ++n) e.line("drop f{}", n);
  }

  prog.main_carrier = M;
  prog.waste_carrier = need_waste ? W : std::string();
  prog.draw_carrier = waste_rows > 0 ? D : std::string();
  st.increases = L.increases;
  st.decreases = L.decreases;
  st.edge_chained = L.chained;
  st.first_needle = L.min_needle + offset;
  st.last_needle = L.max_needle + offset;
  prog.text = std::move(e.out);

  return verified(std::move(prog));
}

}  // namespace knitforge
