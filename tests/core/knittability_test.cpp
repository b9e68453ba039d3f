#include "knitforge/core/knittability.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "knitforge/util/errors.h"

using namespace knitforge;

namespace {

// A tiny, independent map -> mesh builder for hand-made test meshes (so the
// core tests do not depend on convert/). Rows are given top row first, as
// drawn; chars: K knit, < short-row-left, > short-row-right, I increase,
// D decrease, . collapsed, space empty. Merges follow docs/representations.md.
struct Built {
  StitchMesh mesh;
  std::vector<std::vector<int>> id;  // [row][col] -> stitch or -1
  int at(int r, int c) const { return id[r][c]; }
};

int find(std::vector<int>& p, int x) {
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}

bool stitch_char(char ch) { return ch != '.' && ch != ' '; }

StitchType char_type(char ch) {
  switch (ch) {
    case '<': return StitchType::ShortRowLeft;
    case '>': return StitchType::ShortRowRight;
    case 'I': return StitchType::Increase;
    case 'D': return StitchType::Decrease;
    default: return StitchType::Knit;
  }
}

Built build(std::vector<std::string> top_first, std::vector<int> dirs = {}, bool labels = true) {
  std::vector<std::string> g(top_first.rbegin(), top_first.rend());
  const int rows = static_cast<int>(g.size()), cols = static_cast<int>(g[0].size());
  if (dirs.empty()) {
    for (int r = 0; r < rows; ++r) dirs.push_back(r % 2 == 0 ? 1 : -1);
  }
  auto V = [&](int i, int j) { return i * (cols + 1) + j; };
  std::vector<int> p((rows + 1) * (cols + 1));
  std::iota(p.begin(), p.end(), 0);
  auto merge = [&](int a, int b) { p[find(p, a)] = find(p, b); };
  auto cell = [&](int r, int c) { return (r >= 0 && r < rows && c >= 0 && c < cols) ? g[r][c] : ' '; };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const char ch = g[r][c];
      if (ch == '<') merge(V(r, c), V(r + 1, c));
      if (ch == '>') merge(V(r, c + 1), V(r + 1, c + 1));
      if (ch == 'I') merge(V(r, c), V(r, c + 1));
      if (ch == 'D') merge(V(r + 1, c), V(r + 1, c + 1));
      if (ch == '.') {
        int l = c - 1, rr = c + 1, d = r - 1, u = r + 1;
        while (cell(r, l) == '.') --l;
        while (cell(r, rr) == '.') ++rr;
        while (cell(d, c) == '.') --d;
        while (cell(u, c) == '.') ++u;
        const bool in_row = stitch_char(cell(r, l)) && stitch_char(cell(r, rr));
        const bool in_col = stitch_char(cell(d, c)) && stitch_char(cell(u, c));
        if (in_row) merge(V(r, c), V(r, c + 1)), merge(V(r + 1, c), V(r + 1, c + 1));
        if (in_col) merge(V(r, c), V(r + 1, c)), merge(V(r, c + 1), V(r + 1, c + 1));
      }
    }
  }
  Built b;
  b.id.assign(rows, std::vector<int>(cols, -1));
  std::vector<int> vid((rows + 1) * (cols + 1), -1);
  std::vector<Vec3> sum((rows + 1) * (cols + 1), Vec3::Zero());
  std::vector<int> cnt((rows + 1) * (cols + 1), 0);
  for (int i = 0; i <= rows; ++i) {
    for (int j = 0; j <= cols; ++j) {
      sum[find(p, V(i, j))] += Vec3(j, i, 0);
      ++cnt[find(p, V(i, j))];
    }
  }
  auto vert = [&](int i, int j) {
    const int root = find(p, V(i, j));
    if (vid[root] < 0) {
      vid[root] = b.mesh.num_vertices();
      b.mesh.vertices.push_back(sum[root] / cnt[root]);
    }
    return vid[root];
  };
  for (int r = 0; r < rows; ++r) {
    for (int k = 0; k < cols; ++k) {
      const int c = dirs[r] > 0 ? k : cols - 1 - k;
      const char ch = g[r][c];
      if (!stitch_char(ch)) continue;
      Stitch s;
      s.type = char_type(ch);
      s.direction = static_cast<int8_t>(dirs[r]);
      if (labels) s.course = r, s.wale = c;
      const int bl = vert(r, c), br = vert(r, c + 1), tr = vert(r + 1, c + 1), tl = vert(r + 1, c);
      switch (s.type) {
        case StitchType::Knit: s.v = {bl, br, tr, tl}; break;
        case StitchType::ShortRowLeft: s.v = {bl, br, tr, -1}; break;
        case StitchType::ShortRowRight: s.v = {bl, br, tl, -1}; break;
        case StitchType::Increase: s.v = {bl, tr, tl, -1}; break;
        case StitchType::Decrease: s.v = {bl, br, tr, -1}; break;
      }
      b.id[r][c] = b.mesh.num_stitches();
      b.mesh.stitches.push_back(s);
    }
  }
  return b;
}

std::vector<int> count_vector(const KnittabilityReport& r) { return {r.counts.begin(), r.counts.end()}; }

/// Only the listed rules fire, with the given counts.
void expect_only(const KnittabilityReport& rep, std::vector<std::pair<KnitRule, int>> expected) {
  std::vector<int> want(kNumKnitRules, 0);
  for (auto [r, n] : expected) want[static_cast<int>(r)] = n;
  EXPECT_EQ(count_vector(rep), want) << rep.text();
}

const KnittabilityViolation* first_of(const KnittabilityReport& rep, KnitRule r) {
  for (const auto& v : rep.violations) {
    if (v.rule == r) return &v;
  }
  return nullptr;
}

}  // namespace

TEST(Knittability, RuleIdsAreUniqueAndRoundTrip) {
  std::set<std::string> ids;
  for (int i = 0; i < kNumKnitRules; ++i) {
    const auto r = static_cast<KnitRule>(i);
    ids.insert(std::string(rule_id(r)));
    EXPECT_EQ(parse_rule_id(rule_id(r)), r);
  }
  EXPECT_EQ(static_cast<int>(ids.size()), kNumKnitRules);
  EXPECT_EQ(rule_id(KnitRule::CyclicRow), "cyclic-row");
  EXPECT_THROW(parse_rule_id("no-such-rule"), InvalidInput);
}

TEST(Knittability, PlainSheetIsClean) {
  const Built b = build({"KKKKK", "KKKKK", "KKKKK", "KKKKK"});
  const auto rep = check_knittability(b.mesh);
  EXPECT_TRUE(rep.ok());
  EXPECT_TRUE(rep.violations.empty());
  EXPECT_EQ(rep.text(), "knittable: no violations\n");
}

TEST(Knittability, ShortRowPairIsClean) {
  const Built b = build({"KKKK", ".<KK", ".<KK", "KKKK"});
  ASSERT_EQ(b.mesh.num_stitches(), 14);
  const auto rep = check_knittability(b.mesh);
  EXPECT_TRUE(rep.violations.empty()) << rep.text();
  // Mirrored: a short row turning on the right.
  const Built m = build({"KKKK", "KK>.", "KK>.", "KKKK", "KKKK"});
  const auto rm = check_knittability(m.mesh);
  EXPECT_TRUE(rm.violations.empty()) << rm.text();
}

TEST(Knittability, TwoSeparatedShortRowPairsInOneWaleAreClean) {
  // Pairs at rows 1-2 and 5-6 in column 1, separated by two full courses.
  const Built b = build({"KKKK", ".<KK", ".<KK", "KKKK", "KKKK", ".<KK", ".<KK", "KKKK"});
  const auto rep = check_knittability(b.mesh);
  EXPECT_TRUE(rep.violations.empty()) << rep.text();
}

TEST(Knittability, ShortColumnIsClean) {
  const Built b = build({"KK.KK", "KKDKK", "KKKKK", "KKIKK", "KK.KK"});
  const auto rep = check_knittability(b.mesh);
  EXPECT_TRUE(rep.violations.empty()) << rep.text();
  EXPECT_EQ(count_stitch_types(b.mesh)[static_cast<int>(StitchType::Increase)], 1);
}

TEST(Knittability, MalformedAdjacency) {
  Built b = build({"KK"});
  // Rotate the corners of stitch 1: its edge towards stitch 0 becomes its Bottom side.
  auto& v = b.mesh.stitches[1].v;
  v = {v[3], v[0], v[1], v[2]};
  const auto rep = check_knittability(b.mesh);
  ASSERT_EQ(rep.counts[static_cast<int>(KnitRule::MalformedAdjacency)], 1) << rep.text();
  const auto* m = first_of(rep, KnitRule::MalformedAdjacency);
  EXPECT_EQ(m->stitches, (std::vector<int>{0, 1}));
  EXPECT_EQ(m->cells, (std::vector<GridCell>{{0, 0}, {0, 1}}));
  EXPECT_NE(m->message.find("Right side of stitch 0"), std::string::npos) << m->message;
  EXPECT_NE(m->message.find("Bottom side of stitch 1"), std::string::npos) << m->message;
  EXPECT_FALSE(rep.ok());
}

TEST(Knittability, CyclicRow) {
  // One course of 4 stitches around a cylinder.
  StitchMesh m;
  const int n = 4;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.vertices.emplace_back(std::cos(a), std::sin(a), 0);
  }
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    m.vertices.emplace_back(std::cos(a), std::sin(a), 1);
  }
  for (int i = 0; i < n; ++i) {
    Stitch s;
    s.v = {i, (i + 1) % n, n + (i + 1) % n, n + i};
    m.stitches.push_back(s);
  }
  const auto rep = check_knittability(m);
  expect_only(rep, {{KnitRule::CyclicRow, 1}});
  EXPECT_EQ(rep.violations[0].stitches, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_NEAR(rep.violations[0].position.norm(), 0.5, 1e-12);  // centre of the ring, z = 0.5
}

TEST(Knittability, CyclicColumn) {
  // One wale of 4 stitches that closes on itself (a ring around the x axis).
  StitchMesh m;
  const int n = 4;
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      m.vertices.emplace_back(side, std::cos(a), std::sin(a));
    }
  }
  for (int i = 0; i < n; ++i) {
    Stitch s;
    s.direction = i % 2 == 0 ? 1 : -1;
    s.v = {i, n + i, n + (i + 1) % n, (i + 1) % n};
    m.stitches.push_back(s);
  }
  const auto rep = check_knittability(m);
  expect_only(rep, {{KnitRule::CyclicColumn, 1}});
}

TEST(Knittability, HelixIsHelicalRowsAndColumns) {
  // A strip wound around a cylinder: stitch k's Top neighbour is stitch k+4
  // of the same (single) course.
  StitchMesh m;
  const int per_turn = 4, stitches = 12;
  for (int j = 0; j <= stitches + per_turn + 1; ++j) {
    const double a = 2 * M_PI * j / per_turn;
    m.vertices.emplace_back(std::cos(a), std::sin(a), 0.25 * j);
  }
  for (int k = 0; k < stitches; ++k) {
    Stitch s;
    s.v = {k, k + 1, k + per_turn + 1, k + per_turn};
    m.stitches.push_back(s);
  }
  const auto rep = check_knittability(m);
  expect_only(rep, {{KnitRule::HelicalRows, 1}, {KnitRule::HelicalColumns, 1}});
  const auto* h = first_of(rep, KnitRule::HelicalRows);
  EXPECT_EQ(h->stitches, (std::vector<int>{0, 4}));  // stitch 0 is joined to stitch 4 above it
  const auto* c = first_of(rep, KnitRule::HelicalColumns);
  EXPECT_EQ(c->stitches.size(), 8u);  // four column-order edges around the cylinder
}

TEST(Knittability, InconsistentDirection) {
  Built b = build({"KKK", "KKK"});
  b.mesh.stitches[b.at(0, 0)].direction = -1;
  const auto rep = check_knittability(b.mesh);
  ASSERT_EQ(rep.counts[static_cast<int>(KnitRule::InconsistentDirection)], 1) << rep.text();
  EXPECT_EQ(first_of(rep, KnitRule::InconsistentDirection)->stitches, (std::vector<int>{b.at(0, 0)}));
  EXPECT_EQ(first_of(rep, KnitRule::InconsistentDirection)->cells, (std::vector<GridCell>{{0, 0}}));
  EXPECT_FALSE(rep.ok());
}

TEST(Knittability, BetweenRowContinuity) {
  // Both courses left to right: the second does not start above the end of the first.
  const Built b = build({"KKK", "KKK"}, {1, 1});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::BetweenRowContinuity, 1}});
  EXPECT_EQ(rep.violations[0].stitches, (std::vector<int>{b.at(0, 2), b.at(1, 0)}));
  EXPECT_NE(rep.violations[0].message.find("2 other stitches"), std::string::npos) << rep.violations[0].message;
}

TEST(Knittability, GapInACourseIsInRowAndBetweenRowContinuity) {
  const Built b = build({"KKKKK", "KK KK"});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::InRowContinuity, 1}, {KnitRule::BetweenRowContinuity, 1}});
  EXPECT_EQ(first_of(rep, KnitRule::InRowContinuity)->stitches,
            (std::vector<int>{b.at(0, 0), b.at(0, 1), b.at(0, 3), b.at(0, 4)}));
  // Without course labels the gap is only a break of the one-stroke order.
  const Built u = build({"KKKKK", "KK KK"}, {}, false);
  expect_only(check_knittability(u.mesh), {{KnitRule::BetweenRowContinuity, 1}});
}

TEST(Knittability, FirstCourseRightToLeftIsAWarning) {
  const Built b = build({"KKK", "KKK"}, {-1, 1});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::FirstCourseDirection, 1}});
  EXPECT_TRUE(rep.ok());
  EXPECT_EQ(rep.num_warnings(), 1);
  EXPECT_EQ(rep.violations[0].severity, Severity::Warning);
  EXPECT_EQ(rep.violations[0].stitches, (std::vector<int>{0}));
  EXPECT_NE(rep.text().find("warning [first-course-direction]"), std::string::npos);
}

TEST(Knittability, BoundaryApex) {
  const Built b = build({"KKK", "<KK", "<KK", "KKK"});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::BoundaryApex, 2}});
  EXPECT_EQ(rep.violations[0].stitches, (std::vector<int>{b.at(1, 0)}));
  EXPECT_EQ(rep.violations[1].stitches, (std::vector<int>{b.at(2, 0)}));
}

TEST(Knittability, NeighbouringIncreases) {
  const Built b = build({"KKKKKK", "KKIIKK", "KK..KK"});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::NeighbouringIncreases, 1}});
  const int a = b.at(1, 2), c = b.at(1, 3);
  EXPECT_EQ(rep.violations[0].stitches, (std::vector<int>{std::min(a, c), std::max(a, c)}));
  // Separated by a regular stitch they are fine.
  const Built ok = build({"KKKKKKK", "KKIKIKK", "KK.K.KK"});
  EXPECT_TRUE(check_knittability(ok.mesh).violations.empty()) << check_knittability(ok.mesh).text();
}

TEST(Knittability, NeighbouringDecreases) {
  const Built b = build({"KK..KK", "KKDDKK", "KKKKKK"});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::NeighbouringDecreases, 1}});
}

TEST(Knittability, FourStackedShortRowEnds) {
  const Built b = build({"KKKK", ".<KK", ".<KK", ".<KK", ".<KK", "KKKK"});
  const auto rep = check_knittability(b.mesh);
  expect_only(rep, {{KnitRule::StackedShortRowEnds, 1}});
  EXPECT_EQ(rep.violations[0].stitches, (std::vector<int>{b.at(1, 1), b.at(2, 1), b.at(3, 1), b.at(4, 1)}));
}

TEST(Knittability, UnpairedShortRowEnd) {
  // The short row going left ends in a short-row-left stitch, but the next
  // course is a full one: the turn has no partner.
  const Built b = build({"KKKK", ".<KK", "KKKK"});
  const auto rep = check_knittability(b.mesh);
  ASSERT_EQ(rep.counts[static_cast<int>(KnitRule::UnpairedShortRowEnd)], 1) << rep.text();
  EXPECT_EQ(first_of(rep, KnitRule::UnpairedShortRowEnd)->stitches, (std::vector<int>{b.at(1, 1)}));
  // Three stacked ends: the top one is the odd one out.
  const Built t = build({"KKKK", ".<KK", ".<KK", ".<KK", "KKKK"});
  const auto rt = check_knittability(t.mesh);
  ASSERT_EQ(rt.counts[static_cast<int>(KnitRule::UnpairedShortRowEnd)], 1) << rt.text();
  EXPECT_EQ(first_of(rt, KnitRule::UnpairedShortRowEnd)->stitches, (std::vector<int>{t.at(3, 1)}));
  EXPECT_EQ(rt.counts[static_cast<int>(KnitRule::StackedShortRowEnds)], 0);
}

TEST(Knittability, CapKeepsCountsAndOrderIsDeterministic) {
  // Every course left to right: 5 breaks of the one-stroke order.
  const Built b = build({"KKK", "KKK", "KKK", "KKK", "KKK", "KKK"}, {1, 1, 1, 1, 1, 1});
  const auto full = check_knittability(b.mesh);
  EXPECT_EQ(full.counts[static_cast<int>(KnitRule::BetweenRowContinuity)], 5);
  KnittabilityOptions opt;
  opt.max_violations = 2;
  const auto capped = check_knittability(b.mesh, opt);
  EXPECT_EQ(capped.violations.size(), 2u);
  EXPECT_EQ(capped.omitted, 3);
  EXPECT_EQ(capped.counts, full.counts);
  EXPECT_EQ(capped.violations[0].message, full.violations[0].message);
  EXPECT_NE(capped.text().find("3 more violations"), std::string::npos);
  EXPECT_NE(capped.text().find("not knittable: 5 errors"), std::string::npos) << capped.text();
  EXPECT_EQ(check_knittability(b.mesh).text(), full.text());
  // Sorted by smallest stitch within the rule.
  for (size_t i = 1; i < full.violations.size(); ++i) {
    EXPECT_LT(full.violations[i - 1].stitches[0], full.violations[i].stitches[0]);
  }
  opt.max_violations = -1;
  EXPECT_THROW(check_knittability(b.mesh, opt), InvalidInput);
}

TEST(Knittability, NonManifoldMeshThrowsTopologyError) {
  Built b = build({"KK"});
  std::swap(b.mesh.stitches[1].v[1], b.mesh.stitches[1].v[3]);  // flipped orientation
  EXPECT_THROW(check_knittability(b.mesh), TopologyError);
}

TEST(Knittability, EmptyMeshIsClean) { EXPECT_TRUE(check_knittability(StitchMesh{}).violations.empty()); }
