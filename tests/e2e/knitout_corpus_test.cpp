// The machine-end regression corpus (issue 12, item 5): every built-in
// sample map, random maps with short rows and short columns, and the
// short-row and flattened designs of every built-in shape (and of the
// scanned mannequin panel), each knitted for every machine profile. Every
// one must pass the machine's knittability check, give a program, pass the
// virtual machine with every category strict, and knit exactly its map.
// A failing case found later joins the corpus here.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/design/flatten/dart_hints.h"
#include "knitforge/design/pipeline.h"
#include "knitforge/geometry/geodesic_source.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/machine/hand_instructions.h"
#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knit_graph_to_map.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_knittability.h"
#include "knitforge/machine/needle_layout.h"
#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

struct CorpusMap {
  std::string name;
  KnittingMap map;
};

KnittingMap short_row_design(const TriMesh& m, const KnitParams& p, const GeodesicSource& src) {
  ShortRowOptions o;
  o.params = p;
  o.evaluate = false;
  const ShortRowDesign d = design_short_rows(m, src, o);
  EXPECT_TRUE(d.map_check.ok()) << src.description << "\n" << d.map_check.text();
  return d.map;
}

// auto_darts > 0: that many automatic darts, each kept when it lowers the
// RMS distortion (the dome's darts: --auto-darts-rms-only).
KnittingMap flattened_design(const TriMesh& m, const KnitParams& p, int auto_darts) {
  FlattenOptions fo;
  fo.stitch_width = p.stitch_width;
  fo.stitch_height = p.stitch_height;
  DartHintOptions ho;
  ho.require_lower_maximum = false;
  Flattening f =
      auto_darts > 0 ? add_darts_automatically(m, {}, auto_darts, fo, ho).flattening : flatten_surface(m, {}, fo);
  KnitPatternOptions ko;
  ko.evaluate = false;
  const KnitPatternResult k = knit_flattened_pattern(f, m, p, ko);
  EXPECT_TRUE(k.knittability.ok()) << k.knittability.text();
  return k.raster.map;
}

GeodesicSource centre_plane(const TriMesh& m) {
  const BoundingBox b = bounding_box(m);
  return source_from_plane(m, Vec3(1, 0, 0), 0.5 * (b.min.x() + b.max.x()));
}

// Built once for all profiles.
const std::vector<CorpusMap>& corpus() {
  static const std::vector<CorpusMap> maps = [] {
    std::vector<CorpusMap> v;
    for (const auto& n : sample_map_names()) v.push_back({"sample " + n, sample_knitting_map(n)});
    for (uint64_t seed = 1; seed <= 16; ++seed) {
      RandomMapOptions ro;
      ro.seed = 1000 + seed;
      ro.rows = 24 + static_cast<int>(seed % 4) * 6;
      ro.cols = 22 + static_cast<int>(seed % 3) * 4;
      ro.short_row_ends = 2 * static_cast<int>(seed % 7);
      ro.short_columns = static_cast<int>(seed % 6);
      ro.boundary_shaping = seed % 2 == 0;
      v.push_back({"random seed " + std::to_string(ro.seed), random_knitting_map(ro)});
    }
    const KnitParams big{3.5, 2.8};
    for (const char* shape : {"hemisphere", "triple-peak", "monkey-saddle", "disk", "rectangle"}) {
      const TriMesh m = make_shape(shape);
      v.push_back({std::string("shortrow ") + shape, short_row_design(m, big, centre_plane(m))});
    }
    {
      // The half cylinder's default plane cuts it twice (a field ridge): the
      // route takes a source along one straight edge.
      const TriMesh m = make_shape("cylinder-patch", 4.0);
      v.push_back({"shortrow cylinder-patch", short_row_design(m, big, source_from_plane(m, Vec3(0, 0, 1), 0.0))});
    }
    for (const char* shape : {"triple-peak", "monkey-saddle", "disk", "rectangle", "cylinder-patch"}) {
      v.push_back({std::string("flatten ") + shape, flattened_design(make_shape(shape, 4.0), big, 0)});
    }
    // Once refused by the writer (three edge wales ending in one course).
    v.push_back({"flatten hemisphere auto-darts 4", flattened_design(make_shape("hemisphere", 4.0), big, 4)});
    const std::filesystem::path mannequin = std::filesystem::path(KNITFORGE_SHARED_DATA) / "mannequin_front.obj";
    if (std::filesystem::exists(mannequin)) {
      // Ten wales end in one course at the armhole (an edge bind-off chain).
      TriMesh m = read_mesh(mannequin.string());
      for (Vec3& p : m.vertices) p *= 10.0;  // cm -> mm
      v.push_back({"shortrow mannequin_front 3x2",
                   short_row_design(m, KnitParams{3.0, 2.0}, source_from_plane(m, Vec3(1, 0, 0), 0.0))});
    }
    return v;
  }();
  return maps;
}

// One test for all profiles: the corpus (with its designs) is built once
// per process, and CTest runs every test in a process of its own.
TEST(KnitoutCorpus, EveryMapIsKnittedExactlyAsDesignedOnEveryMachine) {
  // what the corpus exercises
  int short_rows = 0, short_columns = 0, chains = 0;
  for (const CorpusMap& c : corpus()) {
    for (CellType t : c.map.cells) {
      short_rows += t == CellType::ShortRowLeft || t == CellType::ShortRowRight;
      short_columns += t == CellType::Increase || t == CellType::Decrease;
    }
    chains += !c.map.tubular() && plan_needle_layout(c.map).chained > 0;
  }
  EXPECT_GT(short_rows, 100);
  EXPECT_GT(short_columns, 20);
  EXPECT_GE(chains, 2);  // bind-off chains are exercised
  EXPECT_GE(corpus().size(), 30u);

  for (const std::string name : {"shima-swg091n2", "kniterate", "generic", "brother-kh868"}) {
    const MachineProfile& prof = machine_profile(name);
    int passed = 0;
    for (const CorpusMap& c : corpus()) {
      SCOPED_TRACE(c.name + " on " + prof.name);
      const KnittabilityReport check = check_machine_knittability(c.map, prof);
      if (prof.manual && c.map.tubular()) {  // a one-bed machine knits no tube (docs/tubes.md)
        EXPECT_FALSE(check.ok());
        passed += !check.ok();
        continue;
      }
      EXPECT_TRUE(check.ok()) << check.text();
      if (!check.ok()) continue;
      if (prof.manual) {
        const HandInstructions h = hand_instructions(c.map, prof);
        EXPECT_EQ(h.rows.size(), static_cast<size_t>(c.map.rows));
        ++passed;
        continue;
      }
      const KnitoutProgram p = write_knitout(c.map, prof);
      // Judged again here, independently of the writer's own verification.
      SimulateOptions so;
      so.strict = all_rules_strict();
      const KnitoutSimulation sim = simulate_knitout(parse_knitout(p.text), prof, so);
      EXPECT_TRUE(sim.ok()) << sim.text();
      EXPECT_EQ(sim.warnings, 0) << sim.text();
      const GraphComparison cmp = compare_knit_graph(sim.graph, c.map);
      EXPECT_TRUE(cmp.ok()) << cmp.text();
      EXPECT_EQ(cmp.fabric_loops, c.map.num_stitches());
      // the writer's counts agree with the machine's
      EXPECT_EQ(sim.stats.transfers, p.stats.xfers);
      EXPECT_EQ(sim.stats.transfers_by_section[0], p.stats.shaping_xfers);
      // and the program's fabric is the map again
      const KnitGraphFabric f = knit_graph_fabric(sim);
      if (c.map.tubular()) {
        EXPECT_NE(f.kind, "sheet");  // a plain tube comes back as a tube, a shaped one is not drawn yet
      } else {
        EXPECT_EQ(f.kind, "sheet") << f.reason;
        EXPECT_EQ(f.map.num_stitches(), c.map.num_stitches());
      }
      passed += sim.ok() && sim.warnings == 0 && cmp.ok();
    }
    EXPECT_EQ(passed, static_cast<int>(corpus().size())) << prof.name;
    std::printf("[ corpus   ] %s: %d of %zu programs pass\n", prof.name.c_str(), passed, corpus().size());
  }
}

}  // namespace
}  // namespace knitforge

namespace knitforge {
namespace {

// One knittability truth: on maps made unknittable (or not) by swapping two
// cells, the machine check and the writer agree, and every program the
// writer returns knits its map (the writer throws Error, not InvalidInput,
// when its own verification fails, which fails this test).
TEST(KnitoutCorpusTruth, CheckAndWriterAgreeOnMutatedMaps) {
  const MachineProfile& prof = machine_profile("shima-swg091n2");
  int refused = 0, written = 0;
  uint64_t state = 12345;
  auto next = [&](uint64_t n) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (state >> 33) % n;
  };
  for (int k = 0; k < 200; ++k) {
    RandomMapOptions ro;
    ro.seed = 500 + static_cast<uint64_t>(k % 20);
    ro.rows = 20;
    ro.cols = 20;
    ro.short_row_ends = 6;
    ro.short_columns = 3;
    ro.boundary_shaping = k % 2 == 0;
    KnittingMap m = random_knitting_map(ro);
    const size_t a = next(m.cells.size()), b = next(m.cells.size());
    std::swap(m.cells[a], m.cells[b]);
    SCOPED_TRACE("mutation " + std::to_string(k));
    const bool ok = check_machine_knittability(m, prof).ok();
    bool wrote = false;
    try {
      const KnitoutProgram p = write_knitout(m, prof);
      wrote = true;
      EXPECT_TRUE(p.comparison && p.comparison->ok());
    } catch (const InvalidInput&) {
      wrote = false;
    }
    EXPECT_EQ(ok, wrote);
    (wrote ? written : refused)++;
  }
  std::printf("[ truth    ] %d mutated maps refused by both, %d written and matching\n", refused, written);
  // both kinds occur, so the agreement is not vacuous
  EXPECT_GT(refused, 20);
  EXPECT_GT(written, 20);
}

}  // namespace
}  // namespace knitforge
