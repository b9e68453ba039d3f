#include "knitforge/machine/hand_instructions.h"

#include <algorithm>
#include <iterator>
#include <set>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {

std::string hand_needle_label(int k, int needle_count) {
  const int half = needle_count / 2;
  return k < half ? fmt::format("L{}", half - k) : fmt::format("R{}", k - half + 1);
}

namespace {

// "L3..R4" for a run of consecutive bed indices, "L3" for one.
std::string range_label(int a, int b, int n) {
  if (a == b) return hand_needle_label(a, n);
  return hand_needle_label(std::min(a, b), n) + ".." + hand_needle_label(std::max(a, b), n);
}

// Comma-separated runs of a sorted list of bed indices.
std::string runs_label(const std::vector<int>& ks, int n) {
  std::string s;
  for (size_t i = 0; i < ks.size();) {
    size_t j = i;
    while (j + 1 < ks.size() && ks[j + 1] == ks[j] + 1) ++j;
    if (!s.empty()) s += ", ";
    s += range_label(ks[i], ks[j], n);
    i = j + 1;
  }
  return s;
}

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string side(int d) { return d > 0 ? "left" : "right"; }

}  // namespace

HandInstructions hand_instructions(const KnittingMap& map, const MachineProfile& prof,
                                   const HandInstructionOptions& opt) {
  validate_machine_profile(prof);
  if (map.tubular())
    throw InvalidInput(fmt::format(
        "the map is a tube (knitted in the round on both beds, docs/tubes.md); the {} has {} and hand instructions "
        "describe flat knitting on one bed: knit the tube on a two-bed machine (knitforge knitout --machine "
        "kniterate), or open it along a wale into a sheet and sew the seam",
        prof.display_name, prof.beds == 1 ? "one needle bed" : "two beds"));
  const int NB = prof.needle_count;
  NeedleLayoutOptions lo;
  lo.max_shift = std::max(1, NB);
  lo.max_stack = std::max(2, prof.max_transfer_stack);
  lo.close_turns = opt.wrap_turns;
  lo.max_closure_loops = 2;
  const NeedleLayout L = plan_needle_layout(map, lo);
  if (!L.problems.empty())
    throw InvalidInput(fmt::format("the {} cannot knit this map: {}", prof.display_name, L.problems.front().message));
  const int width = L.max_needle - L.min_needle + 1;
  if (width > NB)
    throw InvalidInput(fmt::format("the fabric needs {} needles at its widest; the {} has {}",
                                   width, prof.display_name, NB));
  const int offset = (NB - width) / 2 - L.min_needle;
  auto K = [&](int r, int c) { return L.needle_at(r, c) + offset; };
  auto lab = [&](int k) { return hand_needle_label(k, NB); };

  HandInstructions H;
  H.machine = prof.display_name;
  H.stitches = map.num_stitches();
  H.title = fmt::format("{} rows x {} columns, {} stitches, on needles {}", map.rows, map.cols,
                        H.stitches, range_label(L.min_needle + offset, L.max_needle + offset, NB));

  std::vector<int> row0;
  for (int c = 0; c < map.cols; ++c)
    if (L.alive(0, c)) row0.push_back(K(0, c));
  H.setup.push_back(fmt::format("Machine: {} ({} needles, {} .. {}).", prof.display_name, NB,
                                lab(0), lab(NB - 1)));
  H.setup.push_back(fmt::format(
      "Bring needles {} ({} needles) to working position B; all others stay in A.",
      runs_label(row0, NB), row0.size()));
  H.setup.push_back(fmt::format(
      "Cast on over these needles (e-wrap, or a few rows of waste yarn and a ravel cord) and "
      "finish with the carriage on the {} side.",
      side(map.direction[0])));
  H.setup.push_back("Set the row counter to 000. Each row below is one pass of the carriage.");
  bool any_hold = false;
  for (int r = 0; r < map.rows && !any_hold; ++r)
    for (int c = 0; c < map.cols; ++c)
      if (L.alive(r, c) && !is_stitch(map.at(r, c))) any_hold = true;
  if (any_hold)
    H.setup.push_back(
        "Short rows: set the holding cam lever to H (hold) so needles in holding position E do not "
        "knit; needles returned to D knit on the next pass.");

  std::set<int> held_prev;  // wales held during the previous row
  for (int r = 0; r < map.rows; ++r) {
    HandRow hr;
    hr.row = r;
    hr.direction = map.direction[r];
    const LayoutTransition& T = L.transitions[r];
    if (r > 0 && (!T.steps.empty() || !T.starts.empty())) {
      // all moves of all steps, composed per wale: from its old needle to its new one
      std::vector<LayoutMove> moves;
      for (const auto& s : T.steps)
        for (const auto& m : s.moves) {
          auto it = std::find_if(moves.begin(), moves.end(),
                                 [&](const LayoutMove& x) { return x.col == m.col; });
          if (it == moves.end()) moves.push_back(m);
          else it->to = m.to;
        }
      std::set<int> merging;
      for (const auto& m : T.merges) merging.insert(m.col);
      std::vector<LayoutMove> left, right;
      for (const auto& m : moves) (m.to < m.from ? left : right).push_back(m);
      std::sort(left.begin(), left.end(),
                [](const LayoutMove& a, const LayoutMove& b) { return a.from < b.from; });
      std::sort(right.begin(), right.end(),
                [](const LayoutMove& a, const LayoutMove& b) { return a.from > b.from; });
      auto describe = [&](const std::vector<LayoutMove>& ms, const char* dirword) {
        for (size_t i = 0; i < ms.size();) {
          // a run: consecutive needles, same displacement, no merging wale
          size_t j = i;
          const int d = ms[i].to - ms[i].from;
          if (!merging.count(ms[i].col))
            while (j + 1 < ms.size() && !merging.count(ms[j + 1].col) &&
                   ms[j + 1].to - ms[j + 1].from == d &&
                   std::abs(ms[j + 1].from - ms[j].from) == 1)
              ++j;
          const int a = ms[i].from + offset, b = ms[j].from + offset;
          if (merging.count(ms[i].col)) {
            hr.before.push_back(fmt::format(
                "Decrease: move the stitch of {} onto {} (2 stitches on {}, knitted together)",
                lab(a), lab(ms[i].to + offset), lab(ms[i].to + offset)));
          } else {
            hr.before.push_back(fmt::format("Move the stitch{} of {} {} needle{} to the {} (onto {}), starting with {}",
                                            i == j ? "" : "es", range_label(a, b, NB), std::abs(d),
                                            std::abs(d) == 1 ? "" : "s", dirword,
                                            range_label(ms[i].to + offset, ms[j].to + offset, NB),
                                            lab(a)));
          }
          H.hand_transfers += static_cast<int>(j - i + 1);
          i = j + 1;
        }
      };
      describe(left, "left");
      describe(right, "right");
      // needle positions: empty needles for new wales, vacated needles out of work
      std::set<int> before_occ, after_occ;
      for (int c = 0; c < map.cols; ++c) {
        if (L.alive(r - 1, c)) before_occ.insert(K(r - 1, c));
        if (L.alive(r, c) && !std::binary_search(T.starts.begin(), T.starts.end(), c))
          after_occ.insert(K(r, c));
      }
      std::vector<int> vacated;
      for (int k : before_occ)
        if (!after_occ.count(k)) vacated.push_back(k);
      std::vector<int> fresh;
      for (int c : T.starts) fresh.push_back(K(r, c));
      std::sort(fresh.begin(), fresh.end());
      // a vacated needle that becomes a new wale's needle stays in work
      std::vector<int> out;
      for (int k : vacated)
        if (!std::binary_search(fresh.begin(), fresh.end(), k)) out.push_back(k);
      if (!fresh.empty())
        hr.before.push_back(fmt::format(
            "Increase: leave needle{} {} empty in working position B (the new stitch forms there this row)",
            fresh.size() == 1 ? "" : "s", runs_label(fresh, NB)));
      if (!out.empty())
        hr.before.push_back(fmt::format("Push the empty needle{} {} back to non-working position A",
                                        out.size() == 1 ? "" : "s", runs_label(out, NB)));
    }
    // holding
    std::set<int> held_now;
    std::vector<int> to_hold, to_return;
    for (int c = 0; c < map.cols; ++c) {
      if (!L.alive(r, c)) continue;
      if (!is_stitch(map.at(r, c))) {
        held_now.insert(c);
        if (!held_prev.count(c)) to_hold.push_back(K(r, c));
      } else if (held_prev.count(c)) {
        to_return.push_back(K(r, c));
      }
    }
    std::sort(to_hold.begin(), to_hold.end());
    std::sort(to_return.begin(), to_return.end());
    if (!to_return.empty())
      hr.before.push_back(fmt::format("Return {} from hold to upper working position D",
                                      runs_label(to_return, NB)));
    if (!to_hold.empty())
      hr.before.push_back(fmt::format("Push {} to holding position E", runs_label(to_hold, NB)));
    H.held_needle_changes += static_cast<int>(to_hold.size() + to_return.size());
    held_prev = std::move(held_now);

    int nst = 0;
    for (int c = L.first_col[r]; c <= L.last_col[r]; ++c) nst += is_stitch(map.at(r, c));
    int a = K(r, hr.direction > 0 ? L.first_col[r] : L.last_col[r]);
    const int b = K(r, hr.direction > 0 ? L.last_col[r] : L.first_col[r]);
    for (const LayoutChain& ch : L.chains) {
      if (ch.row != r) continue;
      const int n0 = K(r, ch.cols.front()), n1 = K(r, ch.cols.back()), onto = K(r, ch.onto_col);
      const bool at_start = ch.cols.front() == (hr.direction > 0 ? L.first_col[r] : L.last_col[r]);
      const std::string what = fmt::format(
          "cast off the {} stitch{} of {} with the latch tool (chain cast-off from {} to {}), put the last loop "
          "onto {} and push the emptied needles to non-working position A",
          ch.cols.size(), ch.cols.size() == 1 ? "" : "es", range_label(std::min(n0, n1), std::max(n0, n1), NB),
          lab(n0), lab(n1), lab(onto));
      if (at_start) {
        // the carriage side: these are the row's first stitches
        hr.before.push_back("At the carriage side, " + what + " (they are this row's stitches of those wales)");
        nst -= static_cast<int>(ch.cols.size());
        a = onto;
      } else {
        hr.after.push_back("After the row, " + what + " (its wales end here)");
      }
      H.hand_transfers += static_cast<int>(ch.cols.size());
    }
    hr.knit = fmt::format("Carriage {}: knit {} to {} ({} stitch{})",
                          hr.direction > 0 ? "left -> right" : "right -> left", lab(a), lab(b), nst,
                          nst == 1 ? "" : "es");
    if (L.closure_col[r] >= 0) {
      hr.after.insert(hr.after.begin(), fmt::format(
          "Short-row turn: wrap the yarn under held needle {} before the next row (no hole)",
          lab(K(r, L.closure_col[r]))));
      ++H.wraps;
    }
    H.rows.push_back(std::move(hr));
  }
  std::vector<int> live;
  for (int c = 0; c < map.cols; ++c)
    if (L.alive(map.rows - 1, c)) live.push_back(K(map.rows - 1, c));
  if (!held_prev.empty())
    H.finish.push_back("Return all held needles to working position B.");
  H.finish.push_back(fmt::format(
      "Bind off needles {} ({} stitches) with the latch tool or the transfer tool (chain cast-off), "
      "or knit a few rows of waste yarn and take the work off; fasten off the yarn end.",
      runs_label(live, NB), live.size()));
  return H;
}

std::string hand_instructions_text(const HandInstructions& h) {
  std::string o;
  auto out = std::back_inserter(o);
  fmt::format_to(out, "knitforge hand instructions for the {}\n", h.machine);
  fmt::format_to(out, "{}\n", h.title);
  fmt::format_to(out, "{} stitch transfers with the transfer tool, {} hold/return needle moves, {} wraps\n\n",
                 h.hand_transfers, h.held_needle_changes, h.wraps);
  fmt::format_to(out, "Setup\n");
  for (size_t i = 0; i < h.setup.size(); ++i) fmt::format_to(out, "  {}. {}\n", i + 1, h.setup[i]);
  for (const auto& r : h.rows) {
    fmt::format_to(out, "\nRow {} (row counter {:03d} -> {:03d})\n", r.row + 1, r.row, r.row + 1);
    for (const auto& s : r.before) fmt::format_to(out, "  - {}\n", s);
    fmt::format_to(out, "  * {}\n", r.knit);
    for (const auto& s : r.after) fmt::format_to(out, "  - {}\n", s);
  }
  fmt::format_to(out, "\nFinish\n");
  for (const auto& s : h.finish) fmt::format_to(out, "  - {}\n", s);
  return o;
}

std::string hand_instructions_html(const HandInstructions& h) {
  std::string o;
  auto out = std::back_inserter(o);
  fmt::format_to(out,
                 "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                 "<title>Hand instructions: {}</title>\n<style>\n"
                 "body{{font-family:sans-serif;margin:1.5em;color:#111}}\n"
                 "h1{{font-size:1.4em}} table{{border-collapse:collapse;width:100%}}\n"
                 "th,td{{border:1px solid #999;padding:3px 6px;vertical-align:top;text-align:left}}\n"
                 "th{{background:#eee}} td.rc{{font-family:monospace;white-space:nowrap}}\n"
                 "td.done{{width:2em}} ul{{margin:0;padding-left:1.2em}}\n"
                 "tr{{page-break-inside:avoid}} @media print{{body{{margin:0}} th{{background:none}}}}\n"
                 "</style>\n</head>\n<body>\n",
                 html_escape(h.machine));
  fmt::format_to(out, "<h1>Hand instructions for the {}</h1>\n<p>{}</p>\n", html_escape(h.machine),
                 html_escape(h.title));
  fmt::format_to(out, "<p>{} stitch transfers with the transfer tool, {} hold/return needle moves, {} wraps.</p>\n",
                 h.hand_transfers, h.held_needle_changes, h.wraps);
  fmt::format_to(out, "<h2>Setup</h2>\n<ol>\n");
  for (const auto& s : h.setup) fmt::format_to(out, "<li>{}</li>\n", html_escape(s));
  fmt::format_to(out, "</ol>\n<h2>Rows</h2>\n<table>\n<thead><tr><th>Row</th><th>Row counter</th>"
                      "<th>Before the row</th><th>Knit</th><th>After</th><th>Done</th></tr></thead>\n<tbody>\n");
  for (const auto& r : h.rows) {
    fmt::format_to(out, "<tr><td>{}</td><td class=\"rc\">{:03d} &rarr; {:03d}</td><td>", r.row + 1, r.row,
                   r.row + 1);
    if (!r.before.empty()) {
      fmt::format_to(out, "<ul>");
      for (const auto& s : r.before) fmt::format_to(out, "<li>{}</li>", html_escape(s));
      fmt::format_to(out, "</ul>");
    }
    fmt::format_to(out, "</td><td>{}</td><td>", html_escape(r.knit));
    for (size_t i = 0; i < r.after.size(); ++i)
      fmt::format_to(out, "{}{}", i ? "<br>" : "", html_escape(r.after[i]));
    fmt::format_to(out, "</td><td class=\"done\"></td></tr>\n");
  }
  fmt::format_to(out, "</tbody>\n</table>\n<h2>Finish</h2>\n<ul>\n");
  for (const auto& s : h.finish) fmt::format_to(out, "<li>{}</li>\n", html_escape(s));
  fmt::format_to(out, "</ul>\n</body>\n</html>\n");
  return o;
}

}  // namespace knitforge
