#include "knitforge/convert/map_knittability.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/io/knittability_json.h"
#include "knitforge/util/errors.h"
#include "convert/map_test_helpers.h"

using namespace knitforge;
using knitforge::test::make_map;

namespace {


int count(const KnittabilityReport& r, KnitRule rule) { return r.counts[static_cast<int>(rule)]; }

int total(const KnittabilityReport& r) {
  int n = 0;
  for (int c : r.counts) n += c;
  return n;
}

KnittabilityViolation only(const KnittabilityReport& r, KnitRule rule) {
  EXPECT_EQ(total(r), 1) << r.text();
  EXPECT_EQ(count(r, rule), 1) << r.text();
  return r.violations.empty() ? KnittabilityViolation{} : r.violations[0];
}

RandomMapOptions random_options(uint64_t seed) {
  RandomMapOptions o;
  o.seed = seed;
  o.rows = 12 + static_cast<int>(seed % 9);
  o.cols = 12 + static_cast<int>((seed / 3) % 9);
  o.short_row_ends = 2 * static_cast<int>(seed % 4);
  o.short_columns = static_cast<int>((seed / 2) % 3);
  o.boundary_shaping = seed % 5 == 0;
  return o;
}

}  // namespace

TEST(MapKnittability, PlainAndSampleMapsAreClean) {
  EXPECT_TRUE(check_knittability(make_map({"KKKK", "KKKK", "KKKK"})).violations.empty());
  const auto cup = check_knittability(cup_knitting_map());
  EXPECT_TRUE(cup.violations.empty()) << cup.text();
  EXPECT_TRUE(check_knittability(make_map({"KKKK", ".<KK", ".<KK", "KKKK"})).violations.empty());
}

TEST(MapKnittability, InvalidDirection) {
  KnittingMap m = make_map({"KKK", "KKK"});
  m.direction[1] = 0;
  const auto v = only(check_knittability(m), KnitRule::InvalidDirection);
  EXPECT_EQ(v.cells, (std::vector<GridCell>{{1, -1}}));
  EXPECT_TRUE(v.stitches.empty());
}

TEST(MapKnittability, NegativeYarn) {
  KnittingMap m = make_map({"KKK", "KKK"});
  m.set_yarn(0, 1, -2);
  const auto v = only(check_knittability(m), KnitRule::InvalidYarn);
  EXPECT_EQ(v.cells, (std::vector<GridCell>{{0, 1}}));
  EXPECT_NEAR(v.position.x(), 1.5 * 3.5, 1e-12);
  EXPECT_NEAR(v.position.y(), 0.5 * 2.8, 1e-12);
}

TEST(MapKnittability, EmptyRow) {
  const auto v = only(check_knittability(make_map({"KKK", "   ", "KKK"})), KnitRule::EmptyRow);
  EXPECT_EQ(v.cells, (std::vector<GridCell>{{1, -1}}));
}

TEST(MapKnittability, SplitRow) {
  const auto r = check_knittability(make_map({"KKKKK", "KK KK"}));
  const auto v = only(r, KnitRule::SplitRow);
  EXPECT_EQ(v.cells, (std::vector<GridCell>{{0, 1}, {0, 3}}));
  // A short-row end in the middle of a row splits it too.
  const auto r2 = check_knittability(make_map({"KKK", "K<K"}));
  EXPECT_EQ(only(r2, KnitRule::SplitRow).cells, (std::vector<GridCell>{{0, 0}, {0, 1}}));
}

TEST(MapKnittability, CollapsedCrossing) {
  const auto r = check_knittability(make_map({"KKK", "K.K", "KKK"}));
  EXPECT_EQ(only(r, KnitRule::CollapsedCrossing).cells, (std::vector<GridCell>{{1, 1}}));
}

TEST(MapKnittability, CornerContactIsMapTopology) {
  const auto r = check_knittability(make_map({" K", "K "}));
  const auto v = only(r, KnitRule::MapTopology);
  EXPECT_NE(v.message.find("valid stitch mesh"), std::string::npos);
  EXPECT_FALSE(r.ok());
}

TEST(MapKnittability, MeshViolationsNameTheMapCells) {
  KnittingMap m = make_map({"KKK", "KKK"});
  m.direction = {1, 1};
  const auto r = check_knittability(m);
  const auto v = only(r, KnitRule::BetweenRowContinuity);
  EXPECT_EQ(v.cells, (std::vector<GridCell>{{0, 2}, {1, 0}}));
  // The same cells as the mesh's own (course, wale) labels.
  const StitchMesh mesh = map_to_stitch_mesh_topology(m, {});
  for (size_t i = 0; i < v.stitches.size(); ++i) {
    EXPECT_EQ(mesh.stitches[v.stitches[i]].course, v.cells[i].row);
    EXPECT_EQ(mesh.stitches[v.stitches[i]].wale, v.cells[i].col);
  }
  // Increases side by side.
  const auto inc = check_knittability(make_map({"KKKKKK", "KKIIKK", "KK..KK"}));
  EXPECT_EQ(only(inc, KnitRule::NeighbouringIncreases).cells, (std::vector<GridCell>{{1, 3}, {1, 2}}));
}

TEST(MapKnittability, StructuralErrorsThrow) {
  KnittingMap m = make_map({"KKK"});
  m.direction.push_back(1);
  EXPECT_THROW(check_knittability(m), InvalidInput);
  KnittingMap c = make_map({"KKK"});
  c.cells.pop_back();
  EXPECT_THROW(check_knittability(c), InvalidInput);
}

TEST(MapKnittability, RandomMapsAreCleanAndMutationsAreCaught) {
  std::mt19937_64 rng(7);
  int flips = 0, unpaired = 0, increases = 0;
  for (uint64_t seed = 1; seed <= 100; ++seed) {
    const KnittingMap map = random_knitting_map(random_options(seed));
    const auto rep = check_knittability(map);
    ASSERT_TRUE(rep.violations.empty()) << "seed " << seed << ":\n" << rep.text();

    // 1. Flip the direction of one row (not the first): the stroke breaks.
    {
      KnittingMap m = map;
      const int r = 1 + static_cast<int>(rng() % (m.rows - 1));
      m.direction[r] = static_cast<int8_t>(-m.direction[r]);
      const auto f = check_knittability(m);
      EXPECT_FALSE(f.ok()) << "seed " << seed << " row " << r;
      EXPECT_GT(count(f, KnitRule::BetweenRowContinuity), 0) << f.text();
      ++flips;
    }
    // 2. Leave a short-row end without its partner: the course above the
    //    lower end of the lowest pair no longer turns there but runs on to
    //    the fabric edge (its upper end and the collapsed cells beyond it
    //    become regular stitches).
    for (int r = 0; r + 1 < map.rows; ++r) {
      bool done = false;
      for (int c = 0; c < map.cols; ++c) {
        const CellType t = map.at(r, c);
        if ((t == CellType::ShortRowLeft || t == CellType::ShortRowRight) && map.at(r + 1, c) == t) {
          KnittingMap m = map;
          m.at(r + 1, c) = CellType::Knit;
          const int step = t == CellType::ShortRowLeft ? -1 : 1;
          for (int k = c + step; m.contains(r + 1, k) && m.at(r + 1, k) == CellType::Collapsed; k += step) {
            m.at(r + 1, k) = CellType::Knit;
          }
          const auto u = check_knittability(m);
          EXPECT_FALSE(u.ok()) << "seed " << seed << " cell " << r + 1 << "," << c;
          // Inside nested short rows the edit can leave a stitch degenerate
          // (reported as map-topology); take the first pair where it does not.
          if (count(u, KnitRule::MapTopology) > 0) continue;
          EXPECT_GE(count(u, KnitRule::UnpairedShortRowEnd), 1) << "seed " << seed << "\n" << u.text();
          ++unpaired;
          done = true;
          break;
        }
      }
      if (done) break;
    }
    // 3. Put a second increase right next to an increase.
    for (int r = 1; r < map.rows; ++r) {
      bool done = false;
      for (int c = 1; c + 2 < map.cols; ++c) {
        if (map.at(r, c) != CellType::Increase || map.at(r, c + 1) != CellType::Knit) continue;
        bool wale_below = true;
        for (int k = 0; k < r; ++k) wale_below = wale_below && map.at(k, c + 1) == CellType::Knit;
        if (!wale_below) continue;
        KnittingMap m = map;
        m.at(r, c + 1) = CellType::Increase;
        for (int k = 0; k < r; ++k) m.at(k, c + 1) = CellType::Collapsed;
        const auto n = check_knittability(m);
        EXPECT_FALSE(n.ok());
        EXPECT_EQ(count(n, KnitRule::NeighbouringIncreases), 1) << "seed " << seed << "\n" << n.text();
        ++increases;
        done = true;
        break;
      }
      if (done) break;
    }
  }
  EXPECT_EQ(flips, 100);
  EXPECT_GT(unpaired, 30);
  EXPECT_GT(increases, 10);
}

TEST(KnittabilityJson, ReportRoundTrips) {
  KnittingMap m = make_map({"KKK", "KKK"});
  m.direction = {-1, -1};  // first course right to left (warning) and a break (error)
  const auto rep = check_knittability(m);
  ASSERT_EQ(rep.num_errors(), 1) << rep.text();
  ASSERT_EQ(rep.num_warnings(), 1);
  const nlohmann::json j = to_json(rep);
  EXPECT_EQ(j["knittable"], false);
  EXPECT_EQ(j["errors"], 1);
  EXPECT_EQ(j["warnings"], 1);
  EXPECT_EQ(j["counts"]["between-row-continuity"], 1);
  EXPECT_EQ(j["counts"]["first-course-direction"], 1);
  EXPECT_EQ(j["counts"].size(), 2u);
  ASSERT_EQ(j["violations"].size(), 2u);
  const auto& v = j["violations"][0];
  EXPECT_EQ(v["rule"], "between-row-continuity");
  EXPECT_EQ(v["severity"], "error");
  EXPECT_EQ(v["stitches"], nlohmann::json({2, 3}));
  EXPECT_EQ(v["cells"], nlohmann::json({{0, 0}, {1, 2}}));
  EXPECT_EQ(v["position"].size(), 3u);
  EXPECT_EQ(j["violations"][1]["severity"], "warning");

  const KnittabilityReport back = knittability_report_from_json(nlohmann::json::parse(j.dump()));
  EXPECT_EQ(back.counts, rep.counts);
  ASSERT_EQ(back.violations.size(), rep.violations.size());
  for (size_t i = 0; i < rep.violations.size(); ++i) {
    EXPECT_EQ(back.violations[i].rule, rep.violations[i].rule);
    EXPECT_EQ(back.violations[i].severity, rep.violations[i].severity);
    EXPECT_EQ(back.violations[i].stitches, rep.violations[i].stitches);
    EXPECT_EQ(back.violations[i].cells, rep.violations[i].cells);
    EXPECT_EQ(back.violations[i].message, rep.violations[i].message);
    EXPECT_TRUE(back.violations[i].position.isApprox(rep.violations[i].position));
  }
  EXPECT_EQ(to_json(back).dump(), j.dump());
  EXPECT_EQ(to_json(check_knittability(make_map({"KK"})))["knittable"], true);
  EXPECT_THROW(knittability_report_from_json(nlohmann::json::object()), IOError);
  nlohmann::json bad = j;
  bad["violations"][0]["rule"] = "nope";
  EXPECT_THROW(knittability_report_from_json(bad), IOError);
}

namespace {

KnittingMap tube(int round, int rows) {
  KnittingMap m(rows, round, CellType::Knit);
  m.direction.assign(static_cast<size_t>(rows), 1);
  m.seam.assign(static_cast<size_t>(rows), 0);
  return m;
}

TEST(MapKnittability, ARoundIsLegalInATubeButACyclicCourseIsNotInASheetMesh) {
  const KnittingMap m = tube(8, 4);
  const KnittabilityReport rep = check_knittability(m);
  EXPECT_TRUE(rep.ok()) << rep.text();
  EXPECT_EQ(rep.violations.size(), 0u) << rep.text();
  // the same mesh judged as a sheet: every round is a cyclic course
  const StitchMesh mesh = map_to_stitch_mesh_topology(m, KnitParams{});
  const KnittabilityReport sheet = check_knittability(mesh);
  EXPECT_EQ(count(sheet, KnitRule::CyclicRow), 4) << sheet.text();
  KnittabilityOptions o;
  o.closed_courses = true;
  EXPECT_TRUE(check_knittability(mesh, o).ok()) << check_knittability(mesh, o).text();
}

TEST(MapKnittability, TubeRulesNameTheRowOrCell) {
  KnittingMap odd = tube(7, 3);
  EXPECT_EQ(count(check_knittability(odd), KnitRule::TubeLayout), 1);
  KnittingMap open_start = tube(8, 3);
  open_start.seam[0] = -1;
  open_start.at(0, 0) = CellType::Collapsed;
  EXPECT_GE(count(check_knittability(open_start), KnitRule::TubeLayout), 1);
  KnittingMap hole = tube(8, 3);
  hole.at(1, 5) = CellType::Empty;
  const KnittabilityReport h = check_knittability(hole);
  ASSERT_EQ(count(h, KnitRule::ClosedRow), 1) << h.text();
  EXPECT_EQ(h.violations.front().cells.front(), (GridCell{1, 5}));
  KnittingMap thin = tube(8, 3);  // the back half of round 1 keeps one stitch
  for (int c : {5, 6, 7}) thin.at(1, c) = CellType::Collapsed;
  EXPECT_GE(count(check_knittability(thin), KnitRule::TubeShaping), 1);
  KnittingMap slit = tube(8, 3);  // an open row all round the tube
  slit.seam[1] = -1;
  const KnittabilityReport s = check_knittability(slit);
  EXPECT_EQ(count(s, KnitRule::TubeShaping), 1) << s.text();
  // the next round must start where the last ended
  KnittingMap jump = tube(8, 3);
  jump.seam = {0, 4, 4};
  const KnittabilityReport j = check_knittability(jump);
  EXPECT_EQ(count(j, KnitRule::BetweenRowContinuity), 1) << j.text();
  jump.seam[1] = 7;  // starting one column back from the seam continues the yarn
  jump.seam[2] = 7;
  EXPECT_TRUE(check_knittability(jump).ok()) << check_knittability(jump).text();
}

TEST(MapKnittability, TaperedTubeDecreasesAreKnittableButNotSideBySide) {
  KnittingMap m = tube(12, 5);
  m.at(2, 2) = CellType::Decrease;
  for (int r = 3; r < 5; ++r) m.at(r, 2) = CellType::Collapsed;
  EXPECT_TRUE(check_knittability(m).ok()) << check_knittability(m).text();
  m.at(2, 3) = CellType::Decrease;  // a neighbour decreasing in the same round
  for (int r = 3; r < 5; ++r) m.at(r, 3) = CellType::Collapsed;
  EXPECT_FALSE(check_knittability(m).ok());
  // across the seam: columns 11 and 0 are neighbours in a round
  KnittingMap w = tube(12, 5);
  for (int c : {0, 11}) {
    w.at(2, c) = CellType::Decrease;
    for (int r = 3; r < 5; ++r) w.at(r, c) = CellType::Collapsed;
  }
  w.seam.assign(5, 6);
  const KnittabilityReport rw = check_knittability(w);
  EXPECT_FALSE(rw.ok()) << rw.text();
}

}  // namespace

namespace {

TEST(MapKnittability, AHeelWedgeOnPartOfTheRoundIsKnittable) {
  const KnittingMap heel = knitforge::test::heel_tube();
  const KnittabilityReport rep = check_knittability(heel);
  EXPECT_TRUE(rep.ok()) << rep.text();
  // the short rows must stay open: as rounds they hold short-row ends
  KnittingMap closed = heel;
  closed.seam[3] = 0;
  EXPECT_GT(check_knittability(closed).counts[static_cast<size_t>(KnitRule::ClosedRow)], 0);
}

}  // namespace
