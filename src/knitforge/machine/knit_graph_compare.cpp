#include "knitforge/machine/knit_graph_compare.h"

#include <algorithm>

#include <fmt/core.h>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/core/stitch_adjacency.h"

namespace knitforge {

std::vector<int> fabric_loops(const KnitGraph& graph) {
  std::vector<int> out;
  for (int i = 0; i < graph.num_loops(); ++i) {
    const KnitLoop& l = graph.loops[static_cast<size_t>(i)];
    if (l.section != LoopSection::Fabric || l.carriers == 0) continue;
    if (l.kind == LoopKind::Tuck && !(l.on_empty_needle && l.knit_pass)) continue;
    out.push_back(i);
  }
  return out;
}

namespace {

bool shares_vertex(const std::vector<int>& a, const std::vector<int>& b) {
  for (int v : a) {
    if (std::find(b.begin(), b.end(), v) != b.end()) return true;
  }
  return false;
}

// A tube's end: a closed tube (KnittingMap::closed_end) joins each
// closing pair's two loops, and nothing else, in one loop (the closing
// seam); an open tube joins no two loops of its last round except
// neighbours in the round (its chain bind-off).
template <class Report, class Cell>
void check_tube_end(const KnitGraph& graph, const KnittingMap& map, const StitchMesh& mesh, const StitchAdjacency& adj,
                    const std::vector<int>& fab, int n, Report& report, Cell& cell) {
  const int last = map.rows - 1;
  std::vector<int> stitch_at(static_cast<size_t>(map.cols), -1);
  for (int k = 0; k < n; ++k) {
    const Stitch& S = mesh.stitches[static_cast<size_t>(k)];
    if (S.course == last) stitch_at[static_cast<size_t>(S.wale)] = k;
  }
  auto loop_of = [&](int k) { return fab[static_cast<size_t>(k)]; };
  auto child_of = [&](int k) { return graph.loops[static_cast<size_t>(loop_of(k))].child; };
  if (map.closed_end) {
    for (const auto& [f, b] : closing_pairs(map)) {
      const int kf = stitch_at[static_cast<size_t>(f)], kb = stitch_at[static_cast<size_t>(b)];
      if (kf < 0 || kb < 0) continue;  // missing loops: reported by "count"
      const int c = child_of(kf);
      const bool joined = c >= 0 && c == child_of(kb) && graph.parents_of(c).size() == 2;
      if (!joined)
        report("closing", kf, loop_of(kf),
               fmt::format("the tube is closed: {} and {} (the loop opposite it) should be pulled through together by "
                           "one loop of the closing seam, but {}",
                           cell(kf), cell(kb),
                           c < 0 ? std::string("the first is never pulled through")
                                 : c != child_of(kb)
                                       ? fmt::format("they are pulled through by different loops (lines {} and {})",
                                                     graph.loops[static_cast<size_t>(c)].line,
                                                     child_of(kb) >= 0
                                                         ? graph.loops[static_cast<size_t>(child_of(kb))].line
                                                         : 0)
                                       : fmt::format("the loop of line {} also takes {} other loop(s)",
                                                     graph.loops[static_cast<size_t>(c)].line,
                                                     graph.parents_of(c).size() - 2)));
    }
    return;
  }
  // open: two last-round loops under one child must be neighbours in the round
  std::vector<int> first_parent_stitch(static_cast<size_t>(graph.num_loops()), -1);
  for (int k : stitch_at) {
    if (k < 0) continue;
    const int c = child_of(k);
    if (c < 0) continue;
    int& other = first_parent_stitch[static_cast<size_t>(c)];
    if (other < 0) {
      other = k;
    } else if (adj.next_in_course(other) != k && adj.next_in_course(k) != other) {
      report("closing", k, loop_of(k),
             fmt::format("the tube is open at its end, but {} and {} are pulled through together (line {}), as a "
                         "closing seam would join them; mark the last row ':close' if the tube is meant to be closed",
                         cell(other), cell(k), graph.loops[static_cast<size_t>(c)].line));
    }
  }
}

}  // namespace

GraphComparison compare_knit_graph(const KnitGraph& graph, const KnittingMap& map, const CompareOptions& options) {
  const StitchMesh mesh = map_to_stitch_mesh_topology(map, KnitParams{});
  const StitchAdjacency adj(mesh);
  const std::vector<int> fab = fabric_loops(graph);

  GraphComparison out;
  out.map_stitches = mesh.num_stitches();
  out.fabric_loops = static_cast<int>(fab.size());
  const int n = std::min(out.map_stitches, out.fabric_loops);

  std::vector<int> stitch_of_loop(static_cast<size_t>(graph.num_loops()), -1);
  for (int k = 0; k < n; ++k) stitch_of_loop[static_cast<size_t>(fab[static_cast<size_t>(k)])] = k;

  auto report = [&](const char* kind, int stitch, int loop, std::string msg) {
    ++out.mismatches;
    if (options.max_issues > 0 && static_cast<int>(out.issues.size()) >= options.max_issues) return;
    GraphMismatch m;
    m.kind = kind;
    m.stitch = stitch;
    if (stitch >= 0) {
      m.row = mesh.stitches[static_cast<size_t>(stitch)].course;
      m.col = mesh.stitches[static_cast<size_t>(stitch)].wale;
    }
    m.loop = loop;
    m.line = loop >= 0 ? graph.loops[static_cast<size_t>(loop)].line : 0;
    m.message = std::move(msg);
    out.issues.push_back(std::move(m));
  };
  auto cell = [&](int s) {
    const Stitch& st = mesh.stitches[static_cast<size_t>(s)];
    return fmt::format("stitch {} (row {}, column {})", s, st.course, st.wale);
  };

  if (out.fabric_loops != out.map_stitches) {
    const int s = n < out.map_stitches ? n : -1;
    const int l = n < out.fabric_loops ? fab[static_cast<size_t>(n)] : -1;
    report("count", s, l,
           fmt::format("the program knits {} fabric loops but the map has {} stitches{}", out.fabric_loops,
                       out.map_stitches,
                       s >= 0 ? fmt::format("; {} and later have no loop", cell(s))
                              : fmt::format("; the loops from line {} on have no stitch",
                                            graph.loops[static_cast<size_t>(l)].line)));
  }

  // Stitches whose bottom edge touches each vertex (for decreases).
  std::vector<std::vector<int>> bottom_users(static_cast<size_t>(mesh.num_vertices()));
  std::vector<std::vector<int>> bottoms(static_cast<size_t>(mesh.num_stitches()));
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    bottoms[static_cast<size_t>(s)] = bottom_vertices(mesh.stitches[static_cast<size_t>(s)]);
    for (int v : bottoms[static_cast<size_t>(s)]) bottom_users[static_cast<size_t>(v)].push_back(s);
  }

  // A stitch whose wale ends with a free top: no later stitch touches it (the
  // fabric edge narrows there).
  auto free_end = [&](int s) {
    if (adj.neighbor(s, Side::Top) >= 0) return false;
    for (int v : top_vertices(mesh.stitches[static_cast<size_t>(s)])) {
      for (int u : bottom_users[static_cast<size_t>(v)])
        if (u != s) return false;
    }
    return true;
  };

  for (int k = 0; k < n; ++k) {
    const Stitch& S = mesh.stitches[static_cast<size_t>(k)];
    const int li = fab[static_cast<size_t>(k)];
    const KnitLoop& L = graph.loops[static_cast<size_t>(li)];
    // A tube's back half is knitted on the back bed, against the row's
    // direction (the round comes back along the back bed).
    const bool back = map.on_back(S.wale);
    const int machine_dir = back ? -S.direction : S.direction;
    if (map.tubular() && L.needle.is_front_side() == back) {
      report("bed", k, li,
             fmt::format("{} lies on the {} half of the tube but is knitted on needle {}", cell(k),
                         back ? "back" : "front", to_string(L.needle)));
    }
    if (L.direction != machine_dir) {
      report("direction", k, li,
             fmt::format("{} is knitted in direction {} but its map row goes {}{}", cell(k),
                         L.direction > 0 ? '+' : '-', S.direction > 0 ? '+' : '-',
                         back ? " (so its back-bed stitches go the other way)" : ""));
    }
    const bool same_bed = k + 1 < n && map.on_back(mesh.stitches[static_cast<size_t>(k + 1)].wale) == back;
    if (k + 1 < n && same_bed && adj.next_in_course(k) == k + 1) {
      const KnitLoop& L2 = graph.loops[static_cast<size_t>(fab[static_cast<size_t>(k + 1)])];
      if ((L2.slot - L.slot) * machine_dir <= 0) {
        report("course", k + 1, fab[static_cast<size_t>(k + 1)],
               fmt::format("{} follows {} in its course but its loop (needle {}) is not further along in "
                           "direction {} than the previous one (needle {})",
                           cell(k + 1), cell(k), to_string(L2.needle), machine_dir > 0 ? '+' : '-',
                           to_string(L.needle)));
      }
    }
    // Wale: fabric parents.
    const int b = adj.neighbor(k, Side::Bottom);
    const int expected = b >= 0 && b < n ? fab[static_cast<size_t>(b)] : -1;
    bool found_expected = false;
    for (int p : graph.parents_of(li)) {
      const int ps = stitch_of_loop[static_cast<size_t>(p)];
      if (ps < 0) continue;  // not a fabric loop (cast-on, tuck, ...)
      if (p == expected) {
        found_expected = true;
        continue;
      }
      // A wale that ends (no Top neighbour) next to S's bottom edge: merged.
      if (adj.neighbor(ps, Side::Top) < 0 &&
          shares_vertex(top_vertices(mesh.stitches[static_cast<size_t>(ps)]), bottoms[static_cast<size_t>(k)])) {
        continue;
      }
      // An edge bind-off chain: the previous stitch of S's course ends its
      // wale with a free top and its loop was passed over onto S's needle.
      if (adj.next_in_course(ps) == k && free_end(ps)) continue;
      report("wale", k, li,
             fmt::format("{} is pulled through the loop of {} (line {}), which is not below it in the map",
                         cell(k), cell(ps), graph.loops[static_cast<size_t>(p)].line));
    }
    if (b >= 0 && b < n && !found_expected) {
      report("wale", k, li,
             fmt::format("{} is not pulled through the loop of its Bottom neighbour {} (line {})", cell(k),
                         cell(b), graph.loops[static_cast<size_t>(expected)].line));
    }
    // A wale that ends below later stitches (a Decrease, an outside
    // decrease): its loop must be taken by a stitch touching its top.
    if (adj.neighbor(k, Side::Top) < 0) {
      std::vector<int> above;
      for (int v : top_vertices(S)) {
        for (int u : bottom_users[static_cast<size_t>(v)]) above.push_back(u);
      }
      if (!above.empty()) {
        const int child = L.child;
        const int cs = child >= 0 ? stitch_of_loop[static_cast<size_t>(child)] : -1;
        if (cs < 0 || std::find(above.begin(), above.end(), cs) == above.end()) {
          report("decrease", k, li,
                 fmt::format("{} ends its wale but its loop is not merged into a neighbouring wale (it is {})", cell(k),
                             child < 0 ? std::string("never pulled through")
                                       : fmt::format("pulled through by the loop of line {}",
                                                     graph.loops[static_cast<size_t>(child)].line)));
        }
      }
    }
  }
  if (map.tubular() && map.rows > 0) check_tube_end(graph, map, mesh, adj, fab, n, report, cell);
  return out;
}

std::string GraphComparison::text() const {
  std::string s;
  if (ok()) {
    s += fmt::format("knit graph MATCHES the map: {} stitches, {} fabric loops\n", map_stitches, fabric_loops);
  } else {
    s += fmt::format("knit graph DIFFERS from the map: {} mismatch(es); {} map stitches, {} fabric loops\n",
                     mismatches, map_stitches, fabric_loops);
  }
  for (const auto& m : issues) {
    s += fmt::format("  {}: ", m.kind);
    if (m.stitch >= 0) s += fmt::format("map row {} column {}, ", m.row, m.col);
    if (m.line > 0) s += fmt::format("knitout line {}: ", m.line);
    s += m.message + "\n";
  }
  if (static_cast<int>(issues.size()) < mismatches) {
    s += fmt::format("  ({} more mismatches not shown)\n", mismatches - static_cast<int>(issues.size()));
  }
  return s;
}

}  // namespace knitforge
