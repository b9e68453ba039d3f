#include "knitforge/convert/stitch_mesh_to_map.h"

#include <gtest/gtest.h>

#include <ctime>
#include <map>
#include <numeric>

#include "convert/map_test_helpers.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/random_knitting_map.h"
#include "knitforge/convert/sample_knitting_map.h"
#include "knitforge/core/stitch_adjacency.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

const KnitParams kP{};

// The mesh with stitches and vertices renumbered by a deterministic shuffle.
StitchMesh shuffled(const StitchMesh& m, uint64_t seed, std::vector<int>* stitch_perm) {
  auto shuffle = [&seed](std::vector<int>& p) {
    for (size_t i = p.size(); i > 1; --i) {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      std::swap(p[i - 1], p[(seed >> 33) % i]);
    }
  };
  std::vector<int> vp(m.num_vertices()), sp(m.num_stitches());
  std::iota(vp.begin(), vp.end(), 0);
  std::iota(sp.begin(), sp.end(), 0);
  shuffle(vp);
  shuffle(sp);
  StitchMesh out;
  out.vertices.resize(m.vertices.size());
  for (int v = 0; v < m.num_vertices(); ++v) out.vertices[vp[v]] = m.vertices[v];
  out.stitches.resize(m.stitches.size());
  for (int s = 0; s < m.num_stitches(); ++s) {
    Stitch st = m.stitches[s];
    for (int k = 0; k < st.corners(); ++k) st.v[k] = vp[st.v[k]];
    st.course = st.wale = -1;  // the conversion must not rely on them
    out.stitches[sp[s]] = st;
  }
  *stitch_perm = sp;
  return out;
}

}  // namespace

TEST(StitchMeshToMap, MeshMapMeshKeepsTheStitchSequence) {
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    RandomMapOptions o;
    o.seed = seed;
    o.rows = 6 + static_cast<int>(seed % 20);
    o.cols = 8 + static_cast<int>((seed * 5) % 20);
    o.short_row_ends = 2 * static_cast<int>(seed % (o.rows - 2));
    o.short_columns = static_cast<int>(seed % (o.cols / 2));
    KnittingMap m;
    try {
      m = random_knitting_map(o);
    } catch (const InvalidInput&) {
      continue;
    }
    const StitchMesh a = map_to_stitch_mesh_topology(m, kP);
    std::vector<int> perm;
    const StitchMesh shuf = shuffled(a, seed, &perm);
    const KnittingMap back = stitch_mesh_to_map(shuf);
    ASSERT_TRUE(back == m) << "seed " << seed << "\n" << draw_map(m) << "out:\n" << draw_map(back);
    const StitchMesh b = map_to_stitch_mesh_topology(back, kP);
    ASSERT_EQ(a.num_stitches(), b.num_stitches());
    const StitchAdjacency adj_s(shuf), adj_b(b);
    for (int s = 0; s < a.num_stitches(); ++s) {
      const Stitch& x = shuf.stitches[perm[s]];
      const Stitch& y = b.stitches[s];
      ASSERT_EQ(x.type, y.type);
      ASSERT_EQ(x.direction, y.direction);
      for (int k = 0; k < 4; ++k) {
        const int nx = adj_s.neighbor(perm[s], static_cast<Side>(k));
        const int ny = adj_b.neighbor(s, static_cast<Side>(k));
        ASSERT_EQ(nx < 0, ny < 0);
        if (ny >= 0) {
          ASSERT_EQ(nx, perm[ny]);
        }
      }
    }
  }
}

TEST(StitchMeshToMap, UnorderedShortColumnsFollowTheTieBreak) {
  // Columns 1 and 2 never share a course; the lower-starting one goes left.
  const KnittingMap canonical = parse_map({"K.KK", "K.IK", "K..K", "KD.K", "KK.K"});
  KnittingMap swapped = canonical;
  for (int r = 0; r < swapped.rows; ++r) std::swap(swapped.at(r, 1), swapped.at(r, 2));
  StitchMesh a = map_to_stitch_mesh_topology(canonical, kP);
  StitchMesh b = map_to_stitch_mesh_topology(swapped, kP);
  // With the wale labels the mesh carries, each map comes back as it was laid out.
  EXPECT_TRUE(stitch_mesh_to_map(a) == canonical);
  EXPECT_TRUE(stitch_mesh_to_map(b) == swapped) << draw_map(stitch_mesh_to_map(b));
  // Without labels the tie-break decides, the same way for both.
  for (StitchMesh* m : {&a, &b}) {
    for (Stitch& st : m->stitches) st.wale = -1;
  }
  EXPECT_TRUE(stitch_mesh_to_map(a) == canonical);
  EXPECT_TRUE(stitch_mesh_to_map(b) == canonical) << draw_map(stitch_mesh_to_map(b));
}

TEST(StitchMeshToMap, WaleLabelsThatContradictTheMeshAreIgnored) {
  const KnittingMap canonical = parse_map({"KKK", "KKK"});
  StitchMesh m = map_to_stitch_mesh_topology(canonical, kP);
  for (Stitch& st : m.stitches) st.wale = 5 - st.wale;  // Right neighbours would get smaller labels
  EXPECT_TRUE(stitch_mesh_to_map(m) == canonical);
}

TEST(StitchMeshToMap, DirectionDisagreementNamesStitches) {
  StitchMesh m = map_to_stitch_mesh_topology(parse_map({"KKK", "KKK"}), kP);
  m.stitches[4].direction = 1;  // row 1 is right to left
  try {
    stitch_mesh_to_map(m);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("4"), std::string::npos) << w;
    EXPECT_NE(w.find("direction"), std::string::npos) << w;
  }
}

TEST(StitchMeshToMap, TubeColumnsFormACycle) {
  // Four quads around a tube: every one is the Right neighbour of the previous.
  StitchMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i % 4, i / 4, 0);
  for (int k = 0; k < 4; ++k) {
    Stitch s;
    s.v = {k, (k + 1) % 4, 4 + (k + 1) % 4, 4 + k};
    m.stitches.push_back(s);
  }
  try {
    stitch_mesh_to_map(m);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("column"), std::string::npos) << e.what();
  }
}

TEST(StitchMeshToMap, HelixRowsAreRejected) {
  // A strip of quads wound so that quad k's Top neighbour is quad k + 3 of
  // the same course.
  const int n = 8, P = 3;
  StitchMesh m;
  for (int i = 0; i <= n + P; ++i) m.vertices.emplace_back(i, 0, 0);
  for (int k = 0; k < n; ++k) {
    Stitch s;
    s.v = {k, k + 1, k + 1 + P, k + P};
    m.stitches.push_back(s);
  }
  try {
    stitch_mesh_to_map(m);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("helix"), std::string::npos) << w;
    EXPECT_NE(w.find("stitch 0"), std::string::npos) << w;
  }
}

TEST(StitchMeshToMap, EmptyAndNonManifoldMeshes) {
  EXPECT_THROW(stitch_mesh_to_map(StitchMesh{}), InvalidInput);
  StitchMesh m = map_to_stitch_mesh_topology(parse_map({"KK"}), kP);
  m.stitches[1].v[0] = m.stitches[1].v[1];  // repeated corner
  EXPECT_THROW(stitch_mesh_to_map(m), TopologyError);
}

// Speed is measured in bench/bench_convert.cpp, not here.
TEST(StitchMeshToMap, LargeMapRoundTrips) {
#if defined(__SANITIZE_ADDRESS__)
  const int n = 80;  // sanitizer builds are slower
#else
  const int n = 300;
#endif
  RandomMapOptions o;
  o.seed = 11;
  o.rows = n;
  o.cols = n;
  o.short_row_ends = 4 * n / 3;
  o.short_columns = 2 * n / 3;
  const KnittingMap m = random_knitting_map(o);
  const StitchMesh mesh = map_to_stitch_mesh_topology(m, kP);
  const KnittingMap back = stitch_mesh_to_map(mesh);
  EXPECT_TRUE(back == m);
}

namespace {

TEST(StitchMeshToMap, TubesRoundTripExactlyWithSeamsAndShaping) {
  TubeMapOptions o;
  o.round = 16;
  o.rows = 9;
  o.decrease_rounds = 2;
  o.every = 3;
  KnittingMap tapered = tube_knitting_map(o);
  KnittingMap turned = tube_knitting_map({8, 4, 0, 4});
  turned.direction = {1, 1, -1, -1};
  turned.seam = {0, 3, 3, 6};
  for (const KnittingMap& m : {tapered, turned, heel_tube()}) {
    const StitchMesh mesh = map_to_stitch_mesh_topology(m, kP);
    const KnittingMap back = stitch_mesh_to_map(mesh);
    EXPECT_TRUE(back.tubular());
    EXPECT_EQ(back, m);
    EXPECT_EQ(back.seam, m.seam);
  }
  // without wale labels a tube cannot be read
  StitchMesh mesh = map_to_stitch_mesh_topology(turned, kP);
  for (Stitch& s : mesh.stitches) s.wale = -1;
  EXPECT_THROW(stitch_mesh_to_map(mesh), InvalidInput);
}

}  // namespace
