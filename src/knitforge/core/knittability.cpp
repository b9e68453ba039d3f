#include "knitforge/core/knittability.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>

#include "knitforge/core/stitch_adjacency.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr std::string_view kRuleIds[kNumKnitRules] = {
    "malformed-adjacency",    "cyclic-row",
    "cyclic-column",          "helical-rows",
    "helical-columns",        "inconsistent-direction",
    "in-row-continuity",      "between-row-continuity",
    "first-course-direction", "boundary-apex",
    "neighbouring-increases", "neighbouring-decreases",
    "stacked-short-row-ends", "unpaired-short-row-end",
    "collapsed-crossing",     "split-row",
    "invalid-direction",      "invalid-yarn",
    "empty-row",              "map-topology",           "machine-limit",
    "tube-layout",            "closed-row",             "tube-shaping",
};

constexpr std::string_view kSideNames[] = {"Bottom", "Right", "Top", "Left"};

std::string_view side_name(Side s) { return kSideNames[static_cast<int>(s)]; }

bool is_short_row_end(StitchType t) { return t == StitchType::ShortRowLeft || t == StitchType::ShortRowRight; }

/// Course / wale chains of a stitch mesh: each stitch has at most one proper
/// neighbour on each side, so every component is a path or a cycle.
struct Chains {
  std::vector<int> comp;               ///< component id per stitch (ids ordered by smallest stitch)
  std::vector<std::vector<int>> list;  ///< stitches per component, from the first (left / bottom) on
  std::vector<char> cyclic;            ///< per component
};

Chains build_chains(int n, const std::vector<int>& before, const std::vector<int>& after) {
  Chains ch;
  ch.comp.assign(n, -1);
  for (int s = 0; s < n; ++s) {
    if (ch.comp[s] >= 0) continue;
    // Walk back to the first stitch of the chain; a return to s means a cycle.
    int first = s;
    bool cycle = false;
    while (before[first] >= 0) {
      first = before[first];
      if (first == s) {
        cycle = true;
        break;
      }
    }
    const int id = static_cast<int>(ch.list.size());
    ch.list.emplace_back();
    ch.cyclic.push_back(cycle ? 1 : 0);
    std::vector<int>& l = ch.list.back();
    int cur = first;
    do {
      ch.comp[cur] = id;
      l.push_back(cur);
      cur = after[cur];
    } while (cur >= 0 && cur != first);
  }
  return ch;
}

/// Strongly connected components of a directed graph (iterative Tarjan).
/// Returns the component id of every node.
std::vector<int> strongly_connected(int n, const std::vector<std::vector<int>>& out, int* count) {
  std::vector<int> index(n, -1), low(n, 0), comp(n, -1), stack;
  std::vector<char> on_stack(n, 0);
  std::vector<std::pair<int, size_t>> call;
  int next_index = 0, ncomp = 0;
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    call.emplace_back(root, 0);
    index[root] = low[root] = next_index++;
    stack.push_back(root);
    on_stack[root] = 1;
    while (!call.empty()) {
      auto& [v, i] = call.back();
      if (i < out[v].size()) {
        const int w = out[v][i++];
        if (index[w] < 0) {
          index[w] = low[w] = next_index++;
          stack.push_back(w);
          on_stack[w] = 1;
          call.emplace_back(w, 0);
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      const int done = v;
      call.pop_back();
      if (!call.empty()) low[call.back().first] = std::min(low[call.back().first], low[done]);
      if (low[done] == index[done]) {
        int w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = 0;
          comp[w] = ncomp;
        } while (w != done);
        ++ncomp;
      }
    }
  }
  if (count) *count = ncomp;
  return comp;
}

class MeshChecker {
 public:
  MeshChecker(const StitchMesh& m, bool closed_courses)
      : mesh_(m), adj_(m), n_(m.num_stitches()), closed_courses_(closed_courses) {}

  std::vector<KnittabilityViolation> run() {
    build_proper_neighbours();
    rows_ = build_chains(n_, left_, right_);
    cols_ = build_chains(n_, down_, up_);
    if (!closed_courses_) check_cyclic(rows_, KnitRule::CyclicRow, "course", "Left/Right");
    check_cyclic(cols_, KnitRule::CyclicColumn, "wale", "Bottom/Top");
    check_helical_rows();
    check_helical_columns();
    check_directions();
    check_in_row_continuity();
    if (closed_courses_) check_stitch_order();
    else check_one_stroke();
    check_shaping();
    return std::move(out_);
  }

 private:
  std::string describe(int s) const {
    const Stitch& st = mesh_.stitches[s];
    if (st.course >= 0 && st.wale >= 0) return fmt::format("stitch {} (course {}, wale {})", s, st.course, st.wale);
    return fmt::format("stitch {}", s);
  }

  std::string list_stitches(const std::vector<int>& ss, size_t max_shown = 8) const {
    std::string r;
    for (size_t i = 0; i < ss.size() && i < max_shown; ++i) {
      if (i) r += ", ";
      r += std::to_string(ss[i]);
    }
    if (ss.size() > max_shown) r += fmt::format(", ... ({} in all)", ss.size());
    return r;
  }

  void add(KnitRule rule, std::vector<int> stitches, std::string message) {
    KnittabilityViolation v;
    v.rule = rule;
    v.severity = rule_severity(rule);
    Vec3 p = Vec3::Zero();
    bool labelled = !stitches.empty();
    for (int s : stitches) {
      p += stitch_centroid(mesh_, s);
      const Stitch& st = mesh_.stitches[s];
      if (st.course < 0 || st.wale < 0) labelled = false;
    }
    if (!stitches.empty()) p /= static_cast<double>(stitches.size());
    if (labelled) {
      for (int s : stitches) v.cells.push_back({mesh_.stitches[s].course, mesh_.stitches[s].wale});
    }
    v.position = p;
    v.stitches = std::move(stitches);
    v.message = std::move(message);
    out_.push_back(std::move(v));
  }

  void build_proper_neighbours() {
    left_.assign(n_, -1);
    right_.assign(n_, -1);
    down_.assign(n_, -1);
    up_.assign(n_, -1);
    for (int s = 0; s < n_; ++s) {
      for (Side side : edge_sides(mesh_.stitches[s].type)) {
        const int t = adj_.neighbor(s, side);
        if (t < 0) continue;
        const Side ts = adj_.neighbor_side(s, side);
        if (ts == opposite_side(side)) {
          switch (side) {
            case Side::Left: left_[s] = t; break;
            case Side::Right: right_[s] = t; break;
            case Side::Bottom: down_[s] = t; break;
            case Side::Top: up_[s] = t; break;
          }
          continue;
        }
        // Report each malformed edge once: from the stitch with the smaller
        // index (or, for a stitch meeting itself, from the smaller side).
        if (s < t || (s == t && static_cast<int>(side) < static_cast<int>(ts))) {
          std::vector<int> ss{s};
          if (t != s) ss.push_back(t);
          add(KnitRule::MalformedAdjacency, ss,
              fmt::format("the {} side of {} is joined to the {} side of {}; a shared edge must join Right to Left "
                          "or Top to Bottom (check the corner order and types of both stitches)",
                          side_name(side), describe(s), side_name(ts), describe(t)));
        }
      }
    }
  }

  void check_cyclic(const Chains& ch, KnitRule rule, const char* what, const char* sides) {
    for (size_t c = 0; c < ch.list.size(); ++c) {
      if (!ch.cyclic[c]) continue;
      std::vector<int> ss = ch.list[c];
      // Start the cycle at its smallest stitch, keeping the order along it.
      std::rotate(ss.begin(), std::min_element(ss.begin(), ss.end()), ss.end());
      add(rule, ss,
          fmt::format("the {} through {} closes on itself via {} neighbours ({} stitches: {}); a sheet cannot be "
                      "knitted around a loop, cut the mesh open",
                      what, describe(ss.front()), sides, ss.size(), list_stitches(ss)));
    }
  }

  /// Finds the cycles of the order graph whose nodes are the chains of
  /// `nodes` and whose edges come from `cross` (stitch -> stitch in the
  /// other direction), skipping stitches in cyclic chains of `skip`.
  void check_order_cycles(const Chains& nodes, const std::vector<int>& cross, const Chains& skip, KnitRule rule,
                          const char* what) {
    const int m = static_cast<int>(nodes.list.size());
    std::vector<std::vector<int>> out(m), witness(m);
    std::vector<int> self_loop(m, -1);
    for (int s = 0; s < n_; ++s) {
      const int t = cross[s];
      if (t < 0 || skip.cyclic[skip.comp[s]]) continue;
      const int a = nodes.comp[s], b = nodes.comp[t];
      if (a == b) {
        if (self_loop[a] < 0) self_loop[a] = s;
        continue;
      }
      out[a].push_back(b);
      witness[a].push_back(s);
    }
    int ncomp = 0;
    const std::vector<int> scc = strongly_connected(m, out, &ncomp);
    std::vector<int> size(ncomp, 0), first_node(ncomp, -1), loop_node(ncomp, -1);
    for (int a = 0; a < m; ++a) {
      ++size[scc[a]];
      if (first_node[scc[a]] < 0) first_node[scc[a]] = a;
      if (self_loop[a] >= 0 && loop_node[scc[a]] < 0) loop_node[scc[a]] = a;
    }
    for (int k = 0; k < ncomp; ++k) {
      if (loop_node[k] >= 0) {
        const int s = self_loop[loop_node[k]];
        add(rule, {s, cross[s]},
            fmt::format("{} is joined to {} of its own {}: the {} spirals instead of stacking (helix); cut the mesh "
                        "along a {} boundary",
                        describe(cross[s]), describe(s), what, what, what));
        continue;
      }
      if (size[k] < 2) continue;
      // BFS inside the component from its first node back to itself.
      const int start = first_node[k];
      std::vector<int> parent(m, -2), via(m, -1);
      std::vector<int> queue{start};
      int closing = -1, closing_via = -1;
      for (size_t qi = 0; qi < queue.size() && closing < 0; ++qi) {
        const int a = queue[qi];
        for (size_t e = 0; e < out[a].size(); ++e) {
          const int b = out[a][e];
          if (scc[b] != k) continue;
          if (b == start) {
            closing = a;
            closing_via = witness[a][e];
            break;
          }
          if (parent[b] != -2) continue;
          parent[b] = a;
          via[b] = witness[a][e];
          queue.push_back(b);
        }
      }
      std::vector<int> pairs;
      std::vector<int> edges{closing_via};
      for (int a = closing; a != start; a = parent[a]) edges.push_back(via[a]);
      std::reverse(edges.begin(), edges.end());
      for (int s : edges) {
        pairs.push_back(s);
        pairs.push_back(cross[s]);
      }
      add(rule, pairs,
          fmt::format("{} {}s form a cycle in the {} order (each must come after the one before it; stitch pairs "
                      "along the cycle: {}); the {}s wind around like a helix, cut the mesh open",
                      edges.size(), what, what, list_stitches(pairs, 12), what));
    }
  }

  void check_helical_rows() { check_order_cycles(rows_, up_, cols_, KnitRule::HelicalRows, "course"); }
  void check_helical_columns() { check_order_cycles(cols_, right_, rows_, KnitRule::HelicalColumns, "wale"); }

  void check_directions() {
    for (const auto& l : rows_.list) {
      int plus = 0;
      for (int s : l) plus += mesh_.stitches[s].direction > 0 ? 1 : 0;
      const int minus = static_cast<int>(l.size()) - plus;
      if (plus == 0 || minus == 0) continue;
      int majority;
      if (plus != minus) {
        majority = plus > minus ? 1 : -1;
      } else {
        majority = mesh_.stitches[*std::min_element(l.begin(), l.end())].direction;
      }
      std::vector<int> odd;
      for (int s : l) {
        if (mesh_.stitches[s].direction != majority) odd.push_back(s);
      }
      std::sort(odd.begin(), odd.end());
      add(KnitRule::InconsistentDirection, odd,
          fmt::format("the course through {} mixes directions: {} of its {} stitches are knitted {} (stitches {}), "
                      "the others {}; a course is knitted in one pass, give all its stitches one direction",
                      describe(odd.front()), odd.size(), l.size(), majority > 0 ? "right to left" : "left to right",
                      list_stitches(odd), majority > 0 ? "left to right" : "right to left"));
    }
  }

  void check_in_row_continuity() {
    for (const Stitch& st : mesh_.stitches) {
      if (st.course < 0) return;  // labels unknown: the one-stroke check covers the gap
    }
    std::map<int, std::vector<int>> by_label;  // course label -> chain ids (ascending)
    for (size_t c = 0; c < rows_.list.size(); ++c) {
      const int label = mesh_.stitches[rows_.list[c].front()].course;
      by_label[label].push_back(static_cast<int>(c));
    }
    for (const auto& [label, chains] : by_label) {
      if (chains.size() < 2) continue;
      std::vector<int> ends;
      for (int c : chains) {
        ends.push_back(rows_.list[c].front());
        if (rows_.list[c].size() > 1) ends.push_back(rows_.list[c].back());
      }
      std::sort(ends.begin(), ends.end());
      add(KnitRule::InRowContinuity, ends,
          fmt::format("course {} is {} separate runs of stitches (run ends: {}); the yarn would float across the "
                      "gap, join the runs or label them as different courses",
                      label, chains.size(), list_stitches(ends, 12)));
    }
  }

  /// Tubes (KnittabilityOptions::closed_courses): the knitting order is the
  /// stitch order. Stitch k+1 follows stitch k along its course, or k ends
  /// its course (the next stitch along it is not k+1: the course's end, or
  /// a round's last stitch before its seam) and k+1 starts the next course
  /// touching k (a shared corner: the yarn goes straight on).
  void check_stitch_order() {
    for (int k = 0; k + 1 < n_; ++k) {
      if (adj_.next_in_course(k) == k + 1) continue;
      if (mesh_.stitches[k].course == mesh_.stitches[k + 1].course && mesh_.stitches[k].course >= 0) {
        add(KnitRule::BetweenRowContinuity, {k, k + 1},
            fmt::format("{} and {} are knitted one after the other in one course but are not neighbours along it",
                        describe(k), describe(k + 1)));
        continue;
      }
      bool touch = false;
      const Stitch& a = mesh_.stitches[k];
      const Stitch& b = mesh_.stitches[k + 1];
      for (int i = 0; i < a.corners() && !touch; ++i)
        for (int j = 0; j < b.corners() && !touch; ++j) touch = a.v[i] == b.v[j];
      if (!touch) {
        add(KnitRule::BetweenRowContinuity, {k, k + 1},
            fmt::format("the course of {} ends there but the next course starts at {}, which does not touch it: "
                        "the last stitch of a course must neighbour the first stitch of the next (seed §1.2.2); "
                        "in a tube, move the seam or the short row's start",
                        describe(k), describe(k + 1)));
      }
    }
  }

  void check_one_stroke() {
    if (n_ == 0) return;
    std::vector<int> prev(n_);
    std::vector<int> heads;
    for (int s = 0; s < n_; ++s) {
      prev[s] = adj_.previous_stitch(s);
      if (prev[s] < 0) heads.push_back(s);
    }
    std::vector<char> visited(n_, 0);
    int remaining = n_;
    size_t head_i = 0;
    int any_i = 0;
    int start = heads.empty() ? 0 : heads.front();
    if (!heads.empty() && mesh_.stitches[start].direction < 0) {
      add(KnitRule::FirstCourseDirection, {start},
          fmt::format("the first stitch, {}, is knitted right to left; by convention (seed §1.2.1) the first course "
                      "goes left to right: mirror the design or flip every direction",
                      describe(start)));
    }
    while (true) {
      int cur = start, last = start, revisit = -1;
      bool loop = false;
      while (true) {
        visited[cur] = 1;
        --remaining;
        last = cur;
        const int nxt = adj_.next_stitch(cur);
        if (nxt < 0) break;
        if (visited[nxt]) {
          if (nxt == start) {
            loop = true;
          } else {
            revisit = nxt;
          }
          break;
        }
        cur = nxt;
      }
      if (revisit >= 0) {
        add(KnitRule::BetweenRowContinuity, {last, revisit},
            fmt::format("after {} the knitting order continues to {}, which is already knitted; check the "
                        "directions of both courses",
                        describe(last), describe(revisit)));
      }
      if (remaining == 0) break;
      // The next run: an unvisited stitch without a predecessor, else any.
      int next_start = -1;
      while (head_i < heads.size() && visited[heads[head_i]]) ++head_i;
      if (head_i < heads.size()) {
        next_start = heads[head_i];
      } else {
        while (visited[any_i]) ++any_i;
        next_start = any_i;
      }
      std::string why;
      if (loop) {
        why = fmt::format("the knitting order from {} closes into a loop at {}", describe(start), describe(last));
      } else if (revisit >= 0) {
        why = fmt::format("the knitting order stops at {}", describe(last));
      } else {
        why = fmt::format("the knitting order stops at {} (its course ends and its Top neighbour does not start "
                          "the next course)",
                          describe(last));
      }
      add(KnitRule::BetweenRowContinuity, {last, next_start},
          fmt::format("{}; {} and {} other stitches are never reached: the last stitch of a course must neighbour "
                      "the first stitch of the next (seed §1.2.2)",
                      why, describe(next_start), remaining - 1));
      start = next_start;
    }
  }

  void check_shaping() {
    for (int s = 0; s < n_; ++s) {
      const Stitch& st = mesh_.stitches[s];
      if (!is_shaping(st.type)) continue;
      const int a = apex_vertex(st);
      if (adj_.is_boundary_vertex(a)) {
        add(KnitRule::BoundaryApex, {s},
            fmt::format("the apex (vertex {}) of {}, a {}, is on the fabric boundary: the short row / short column "
                        "reaches the edge, so this should be a regular stitch",
                        a, describe(s), name(st.type)));
      }
    }
    for (int s = 0; s < n_; ++s) {
      const int t = right_[s];
      if (t < 0) continue;
      const StitchType a = mesh_.stitches[s].type, b = mesh_.stitches[t].type;
      if (a == StitchType::Increase && b == StitchType::Increase) {
        add(KnitRule::NeighbouringIncreases, {std::min(s, t), std::max(s, t)},
            fmt::format("increases {} and {} are side by side in one course; two neighbouring increases stretch "
                        "the yarn too much (seed §1.4.2): put a regular stitch between them",
                        describe(s), describe(t)));
      } else if (a == StitchType::Decrease && b == StitchType::Decrease) {
        add(KnitRule::NeighbouringDecreases, {std::min(s, t), std::max(s, t)},
            fmt::format("decreases {} and {} are side by side in one course; three or more loops would sit on one "
                        "needle: put a regular stitch between them",
                        describe(s), describe(t)));
      }
    }
    for (const auto& l : cols_.list) {
      const int len = static_cast<int>(l.size());
      // Runs of short-row ends of any kind (stacking) and of one kind (pairing).
      for (int i = 0; i < len;) {
        if (!is_short_row_end(mesh_.stitches[l[i]].type)) {
          ++i;
          continue;
        }
        int j = i;
        while (j < len && is_short_row_end(mesh_.stitches[l[j]].type)) ++j;
        if (j - i >= 4) {
          std::vector<int> run(l.begin() + i, l.begin() + j);
          add(KnitRule::StackedShortRowEnds, run,
              fmt::format("{} short-row ends are stacked in the wale from {} up ({}); more than one turn pair in a "
                          "wale cannot be closed with tucks (seed §1.2.2): move one pair sideways",
                          run.size(), describe(run.front()), list_stitches(run)));
        }
        i = j;
      }
      for (int i = 0; i < len;) {
        const StitchType t = mesh_.stitches[l[i]].type;
        if (!is_short_row_end(t)) {
          ++i;
          continue;
        }
        int j = i;
        while (j < len && mesh_.stitches[l[j]].type == t) ++j;
        // In a tube a round can turn into a short row (or a short row end
        // where the next round goes on): the round's stitch next to the
        // stack is the turn's other half.
        const auto in_round = [&](int k) {
          return k >= 0 && k < len && rows_.cyclic[static_cast<size_t>(rows_.comp[l[k]])];
        };
        const bool round_partner = closed_courses_ && (in_round(i - 1) || in_round(j));
        if ((j - i) % 2 == 1 && !round_partner) {
          const int s = l[j - 1];
          add(KnitRule::UnpairedShortRowEnd, {s},
              fmt::format("{}, a {}, has no partner: a short row turns in two stacked {} stitches (the last of one "
                          "course and the first of the next)",
                          describe(s), name(t), name(t)));
        }
        i = j;
      }
    }
  }

  const StitchMesh& mesh_;
  StitchAdjacency adj_;
  int n_;
  bool closed_courses_ = false;
  std::vector<int> left_, right_, down_, up_;
  Chains rows_, cols_;
  std::vector<KnittabilityViolation> out_;
};

}  // namespace

std::string_view rule_id(KnitRule r) {
  const int i = static_cast<int>(r);
  return i >= 0 && i < kNumKnitRules ? kRuleIds[i] : std::string_view("unknown-rule");
}

KnitRule parse_rule_id(std::string_view id) {
  for (int i = 0; i < kNumKnitRules; ++i) {
    if (kRuleIds[i] == id) return static_cast<KnitRule>(i);
  }
  throw InvalidInput(fmt::format("unknown knittability rule '{}'", id));
}

Severity rule_severity(KnitRule r) {
  return r == KnitRule::FirstCourseDirection ? Severity::Warning : Severity::Error;
}

bool KnittabilityReport::ok() const { return num_errors() == 0; }

int KnittabilityReport::num_errors() const {
  int n = 0;
  for (int i = 0; i < kNumKnitRules; ++i) {
    if (rule_severity(static_cast<KnitRule>(i)) == Severity::Error) n += counts[i];
  }
  return n;
}

int KnittabilityReport::num_warnings() const {
  int n = 0;
  for (int i = 0; i < kNumKnitRules; ++i) {
    if (rule_severity(static_cast<KnitRule>(i)) == Severity::Warning) n += counts[i];
  }
  return n;
}

std::string KnittabilityReport::text() const {
  std::string r;
  for (const KnittabilityViolation& v : violations) {
    r += fmt::format("{} [{}] {}\n", v.severity == Severity::Error ? "error" : "warning", rule_id(v.rule), v.message);
  }
  if (omitted > 0) r += fmt::format("... and {} more violations not listed\n", omitted);
  const int e = num_errors(), w = num_warnings();
  if (e == 0 && w == 0) {
    r += "knittable: no violations\n";
    return r;
  }
  std::string per_rule;
  for (int i = 0; i < kNumKnitRules; ++i) {
    if (counts[i] == 0) continue;
    if (!per_rule.empty()) per_rule += ", ";
    per_rule += fmt::format("{} {}", rule_id(static_cast<KnitRule>(i)), counts[i]);
  }
  r += fmt::format("{}: {} error{}, {} warning{} ({})\n", e == 0 ? "knittable" : "not knittable", e,
                   e == 1 ? "" : "s", w, w == 1 ? "" : "s", per_rule);
  return r;
}

KnittabilityReport make_knittability_report(std::vector<KnittabilityViolation> all, const KnittabilityOptions& opt) {
  if (opt.max_violations < 0) {
    throw InvalidInput(fmt::format("KnittabilityOptions::max_violations is {}; it must be >= 0", opt.max_violations));
  }
  constexpr int kBig = std::numeric_limits<int>::max();
  auto key = [&](const KnittabilityViolation& v) {
    const int s = v.stitches.empty() ? kBig : *std::min_element(v.stitches.begin(), v.stitches.end());
    GridCell c{kBig, kBig};
    for (const GridCell& g : v.cells) {
      if (std::tie(g.row, g.col) < std::tie(c.row, c.col)) c = g;
    }
    return std::make_tuple(static_cast<int>(v.rule), s, c.row, c.col);
  };
  std::vector<std::pair<std::tuple<int, int, int, int>, size_t>> order(all.size());
  for (size_t i = 0; i < all.size(); ++i) order[i] = {key(all[i]), i};
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  KnittabilityReport rep;
  for (const auto& [k, i] : order) {
    KnittabilityViolation& v = all[i];
    v.severity = rule_severity(v.rule);
    ++rep.counts[static_cast<int>(v.rule)];
    if (static_cast<int>(rep.violations.size()) < opt.max_violations) {
      rep.violations.push_back(std::move(v));
    } else {
      ++rep.omitted;
    }
  }
  return rep;
}

KnittabilityReport check_knittability(const StitchMesh& mesh, const KnittabilityOptions& opt) {
  if (opt.max_violations < 0) {
    throw InvalidInput(fmt::format("KnittabilityOptions::max_violations is {}; it must be >= 0", opt.max_violations));
  }
  MeshChecker checker(mesh, opt.closed_courses);
  return make_knittability_report(checker.run(), opt);
}

}  // namespace knitforge
