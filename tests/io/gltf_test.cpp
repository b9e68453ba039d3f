#include "knitforge/io/gltf.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "io/io_test_util.h"
#include "knitforge/render/yarn_tubes.h"

namespace knitforge {
namespace {

using nlohmann::json;
using test::TempDir;

uint32_t u32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<uint8_t>(s[at + static_cast<size_t>(k)]);
  return v;
}
float f32(const std::string& s, size_t at) {
  const uint32_t v = u32(s, at);
  float f;
  std::memcpy(&f, &v, 4);
  return f;
}

// A parsed GLB: the JSON document and the BIN chunk, with the container
// checked on the way (header, chunk lengths and alignment).
struct Glb {
  json doc;
  std::string bin;
};

Glb parse_glb(const std::string& data) {
  Glb g;
  EXPECT_GE(data.size(), 28u);
  EXPECT_EQ(data.substr(0, 4), "glTF");
  EXPECT_EQ(u32(data, 4), 2u);
  EXPECT_EQ(u32(data, 8), data.size());
  const uint32_t json_len = u32(data, 12);
  EXPECT_EQ(json_len % 4, 0u);
  EXPECT_EQ(u32(data, 16), 0x4E4F534Au);
  const std::string text = data.substr(20, json_len);
  const size_t end = text.find_last_of('}');
  EXPECT_NE(end, std::string::npos);
  EXPECT_LT(text.size() - end - 1, 4u);  // at most 3 padding bytes, all spaces
  EXPECT_EQ(text.find_first_not_of(' ', end + 1), std::string::npos);
  g.doc = json::parse(text);
  const size_t bin_at = 20 + json_len;
  const uint32_t bin_len = u32(data, bin_at);
  EXPECT_EQ(bin_len % 4, 0u);
  EXPECT_EQ(u32(data, bin_at + 4), 0x004E4942u);
  EXPECT_EQ(bin_at + 8 + bin_len, data.size());
  g.bin = data.substr(bin_at + 8, bin_len);
  return g;
}

size_t component_size(int type) {
  return type == 5126 || type == 5125 ? 4 : type == 5123 ? 2 : type == 5121 ? 1 : 0;
}
uint16_t u16(const std::string& s, size_t at) {
  return static_cast<uint16_t>(static_cast<uint8_t>(s[at]) | (static_cast<uint8_t>(s[at + 1]) << 8));
}
size_t components(const std::string& t) { return t == "SCALAR" ? 1 : t == "VEC3" ? 3 : t == "VEC4" ? 4 : 0; }

// Checks every accessor against its bufferView and the buffer; returns the
// byte offset of accessor `a`'s data in the BIN chunk.
size_t accessor_offset(const Glb& g, int a) {
  const json& acc = g.doc["accessors"][a];
  const json& view = g.doc["bufferViews"][acc["bufferView"].get<int>()];
  const size_t off = view["byteOffset"].get<size_t>();
  const size_t len = view["byteLength"].get<size_t>();
  EXPECT_EQ(off % 4, 0u);
  EXPECT_LE(off + len, g.bin.size());
  const size_t need = acc["count"].get<size_t>() * component_size(acc["componentType"].get<int>()) *
                      components(acc["type"].get<std::string>());
  EXPECT_GT(need, 0u);
  EXPECT_LE(need, len);
  return off;
}

RenderMesh small_mesh() {
  RenderMesh m;
  m.name = "quad";
  m.mesh.vertices = {{0, 0, 0}, {1.5, 0, 0}, {1.5, 2, 0.25}, {0, 2, -0.5}};
  m.mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  m.normals.assign(4, Vec3(0, 0, 2));  // not unit: written normalised
  m.vertex_colours = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {128, 128, 128}};
  return m;
}

TEST(Glb, ContainerJsonAndDataAreConsistent) {
  TempDir dir;
  std::vector<RenderMesh> meshes = {small_mesh()};
  TubeOptions o;
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 0.5, 0}, {2, 0, 0.3}};
  meshes.push_back(yarn_tube(line, o, 0.4, {200, 100, 50}));
  meshes.back().name = "yarn 0";
  for (size_t v = 0; v < meshes.back().mesh.vertices.size(); ++v) {  // varied vertex colours
    meshes.back().vertex_colours.push_back(
        {static_cast<uint8_t>(v % 256), 100, static_cast<uint8_t>(255 - v % 256)});
  }
  const std::string path = dir.path("m.glb");
  write_glb(path, meshes);
  const Glb g = parse_glb(dir.read("m.glb"));
  EXPECT_EQ(g.doc["asset"]["version"], "2.0");
  ASSERT_EQ(g.doc["meshes"].size(), 2u);
  EXPECT_EQ(g.doc["meshes"][1]["name"], "yarn 0");
  EXPECT_EQ(g.doc["scenes"][0]["nodes"].size(), 2u);
  EXPECT_EQ(g.doc["buffers"][0]["byteLength"].get<size_t>(), g.bin.size());
  for (size_t mi = 0; mi < meshes.size(); ++mi) {
    const RenderMesh& m = meshes[mi];
    const json& prim = g.doc["meshes"][mi]["primitives"][0];
    EXPECT_EQ(prim["mode"], 4);
    const int pos = prim["attributes"]["POSITION"], nrm = prim["attributes"]["NORMAL"],
              col = prim["attributes"]["COLOR_0"], idx = prim["indices"];
    const size_t nv = m.mesh.vertices.size();
    EXPECT_EQ(g.doc["accessors"][pos]["count"].get<size_t>(), nv);
    EXPECT_EQ(g.doc["accessors"][col]["normalized"], true);
    EXPECT_EQ(g.doc["accessors"][col]["componentType"], 5121);
    EXPECT_EQ(g.doc["accessors"][idx]["componentType"], 5125);
    EXPECT_EQ(g.doc["accessors"][idx]["count"].get<size_t>(), 3 * m.mesh.faces.size());
    EXPECT_EQ(g.doc["bufferViews"][g.doc["accessors"][pos]["bufferView"].get<int>()]["target"], 34962);
    EXPECT_EQ(g.doc["bufferViews"][g.doc["accessors"][idx]["bufferView"].get<int>()]["target"], 34963);
    const size_t po = accessor_offset(g, pos), no = accessor_offset(g, nrm), co = accessor_offset(g, col),
                 io = accessor_offset(g, idx);
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < 3; ++k) {
        const float x = f32(g.bin, po + 12 * v + 4 * static_cast<size_t>(k));
        EXPECT_EQ(x, static_cast<float>(m.mesh.vertices[v][k]));
        lo[k] = std::min(lo[k], x);
        hi[k] = std::max(hi[k], x);
      }
      const Vec3 n(f32(g.bin, no + 12 * v), f32(g.bin, no + 12 * v + 4), f32(g.bin, no + 12 * v + 8));
      EXPECT_NEAR(n.norm(), 1.0, 1e-6);
      EXPECT_NEAR(n.dot(m.normals[v].normalized()), 1.0, 1e-6);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(static_cast<uint8_t>(g.bin[co + 4 * v + static_cast<size_t>(k)]),
                  srgb_to_linear_byte(m.vertex_colours[v][static_cast<size_t>(k)]));
      }
      EXPECT_EQ(static_cast<uint8_t>(g.bin[co + 4 * v + 3]), 255);
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(g.doc["accessors"][pos]["min"][k].get<float>(), lo[k]);
      EXPECT_EQ(g.doc["accessors"][pos]["max"][k].get<float>(), hi[k]);
    }
    for (size_t f = 0; f < m.mesh.faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(u32(g.bin, io + 12 * f + 4 * static_cast<size_t>(k)),
                  static_cast<uint32_t>(m.mesh.faces[f][k]));
      }
    }
  }
}

TEST(Glb, FaceColoursAreExpandedAndPlainMeshesUseTheMaterialColour) {
  TempDir dir;
  RenderMesh a = small_mesh();
  a.vertex_colours.clear();
  a.face_colours = {{10, 20, 30}, {200, 100, 0}};
  RenderMesh b = small_mesh();
  b.vertex_colours.clear();
  b.normals.clear();
  b.colour = {255, 255, 0};
  RenderMesh empty;
  write_glb(dir.path("f.glb"), std::vector<RenderMesh>{a, empty, b});
  const Glb g = parse_glb(dir.read("f.glb"));
  ASSERT_EQ(g.doc["meshes"].size(), 2u);  // the empty mesh is skipped
  const json& pa = g.doc["meshes"][0]["primitives"][0];
  const int col = pa["attributes"]["COLOR_0"];
  EXPECT_EQ(g.doc["accessors"][pa["attributes"]["POSITION"].get<int>()]["count"], 6);
  const size_t co = accessor_offset(g, col);
  EXPECT_EQ(static_cast<uint8_t>(g.bin[co + 4 * 3]), srgb_to_linear_byte(200));  // vertex 3 = face 1
  EXPECT_EQ(static_cast<uint8_t>(g.bin[co + 4 * 2 + 2]), srgb_to_linear_byte(30));
  const json& pb = g.doc["meshes"][1]["primitives"][0];
  EXPECT_FALSE(pb["attributes"].contains("COLOR_0"));
  EXPECT_FALSE(pb["attributes"].contains("NORMAL"));
  const json& mat = g.doc["materials"][pb["material"].get<int>()];
  EXPECT_DOUBLE_EQ(mat["pbrMetallicRoughness"]["baseColorFactor"][0].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(mat["pbrMetallicRoughness"]["baseColorFactor"][2].get<double>(), 0.0);
  EXPECT_EQ(srgb_to_linear_byte(255), 255);
  EXPECT_EQ(srgb_to_linear_byte(0), 0);
  EXPECT_EQ(srgb_to_linear_byte(128), 55);  // 0.2158 * 255
}

TEST(Glb, BadInputThrowsAndLeavesNoFile) {
  TempDir dir;
  RenderMesh m = small_mesh();
  m.mesh.faces[1][2] = 9;
  const std::string msg = test::invalid_input([&] { write_glb(dir.path("bad.glb"), std::span(&m, 1)); });
  EXPECT_CONTAINS(msg, "face 1");
  RenderMesh none;
  test::invalid_input([&] { write_glb(dir.path("bad.glb"), std::span(&none, 1)); });
  EXPECT_EQ(dir.num_files(), 0u);
  const RenderMesh ok = small_mesh();
  test::io_error([&] { write_glb(dir.path("no/such/dir/x.glb"), std::span(&ok, 1)); });
}

// One mesh of a write_yarn_glb file put back together in yarn_tube()'s
// vertex numbering: side primitive c's vertex v is vertex c step K + v of
// the tube, the caps primitive's vertex v is vertex R K + v.
struct TubeFromGlb {
  std::vector<std::array<float, 3>> positions, normals;
  std::vector<std::array<int, 3>> faces;
  int side_primitives = 0;
};

TubeFromGlb read_tube(const Glb& g, const json& mesh, size_t K, bool capped) {
  TubeFromGlb t;
  const json& prims = mesh["primitives"];
  const size_t n_side = prims.size() - (capped ? 1 : 0);
  t.side_primitives = static_cast<int>(n_side);
  size_t step = 0, rings = 0;
  for (size_t c = 0; c < prims.size(); ++c) {
    const json& prim = prims[c];
    EXPECT_EQ(prim["mode"], 4);
    EXPECT_FALSE(prim["attributes"].contains("COLOR_0"));
    const int pos = prim["attributes"]["POSITION"], nrm = prim["attributes"]["NORMAL"], idx = prim["indices"];
    const json& pa = g.doc["accessors"][pos];
    const size_t nv = pa["count"].get<size_t>();
    EXPECT_LE(nv, 65535u);
    EXPECT_EQ(g.doc["accessors"][nrm]["count"].get<size_t>(), nv);
    const size_t po = accessor_offset(g, pos), no = accessor_offset(g, nrm), io = accessor_offset(g, idx);
    const bool side = c < n_side;
    if (c == 0) step = nv / K - 1;
    const size_t global0 = side ? c * step * K : rings * K;
    if (side) rings = c * step + nv / K;
    if (t.positions.size() < global0 + nv) {
      t.positions.resize(global0 + nv);
      t.normals.resize(global0 + nv);
    }
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t v = 0; v < nv; ++v) {
      std::array<float, 3> p{}, n{};
      for (size_t k = 0; k < 3; ++k) {
        p[k] = f32(g.bin, po + 12 * v + 4 * k);
        n[k] = f32(g.bin, no + 12 * v + 4 * k);
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
      if (side && v < K && c > 0) {  // the ring shared with the previous primitive
        EXPECT_EQ(t.positions[global0 + v], p) << v;
      }
      t.positions[global0 + v] = p;
      t.normals[global0 + v] = n;
      EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6);
    }
    for (int k = 0; k < 3; ++k) {  // min / max exact, as the spec requires
      EXPECT_EQ(pa["min"][k].get<float>(), lo[k]);
      EXPECT_EQ(pa["max"][k].get<float>(), hi[k]);
    }
    const json& ia = g.doc["accessors"][idx];
    const size_t count = ia["count"].get<size_t>();
    EXPECT_EQ(count % 3, 0u);
    EXPECT_EQ(ia["componentType"], 5123);  // unsigned short
    EXPECT_EQ(g.doc["bufferViews"][ia["bufferView"].get<int>()]["target"], 34963);
    for (size_t f = 0; f < count / 3; ++f) {
      std::array<int, 3> tri{};
      for (size_t k = 0; k < 3; ++k) {
        const uint16_t i = u16(g.bin, io + 2 * (3 * f + k));
        EXPECT_LT(i, nv);
        tri[k] = static_cast<int>(global0 + i);
      }
      t.faces.push_back(tri);
    }
  }
  return t;
}

// write_yarn_glb writes the geometry of yarn_tubes() (rounded to float) with
// exact bounds, unit normals and 16-bit indices, in primitives of at most
// 65535 vertices; one material per yarn in its colour.
TEST(YarnGlb, MatchesTheTubeMeshesSplitIntoPrimitives) {
  TempDir dir;
  YarnModel y;
  // a long wavy yarn: 12 vertices per ring every 0.05 mm over ~400 mm is
  // about 8000 rings, so at least 2 side primitives
  std::vector<Vec3> wave;
  for (int i = 0; i <= 400; ++i) wave.emplace_back(i, 3.0 * std::sin(0.3 * i), 0.5 * std::cos(0.2 * i));
  y.yarns.push_back({5, wave, std::vector<int>(wave.size(), 0)});
  y.yarns.push_back({7, {{0, 0, 0}}, {0}});  // one point: no tube
  y.yarns.push_back({9, {{0, 10, 0}, {4, 10, 1}, {8, 11, 0}}, {0, 0, 0}});
  TubeOptions o;
  o.ring_spacing = 0.05;
  const std::vector<RenderColour> colours = {{200, 30, 30}, {0, 0, 0}, {20, 40, 250}};
  const YarnGlbSummary sum = write_yarn_glb(dir.path("y.glb"), y, KnitParams{}, o, colours);
  const std::vector<RenderMesh> tubes = yarn_tubes(y, KnitParams{}, o, colours);
  EXPECT_EQ(sum.meshes, 2u);
  EXPECT_EQ(sum.vertices, tubes[0].mesh.vertices.size() + tubes[2].mesh.vertices.size());
  EXPECT_EQ(sum.triangles, tubes[0].mesh.faces.size() + tubes[2].mesh.faces.size());
  const Glb g = parse_glb(dir.read("y.glb"));
  EXPECT_EQ(g.doc["buffers"][0]["byteLength"].get<size_t>(), g.bin.size());
  ASSERT_EQ(g.doc["meshes"].size(), 2u);
  EXPECT_EQ(g.doc["meshes"][0]["name"], "yarn 5");
  EXPECT_EQ(g.doc["meshes"][1]["name"], "yarn 9");
  EXPECT_EQ(g.doc["scenes"][0]["nodes"].size(), 2u);
  for (const json& v : g.doc["bufferViews"]) EXPECT_EQ(v["byteOffset"].get<size_t>() % 4, 0u);
  const size_t K = 12;
  int side_primitives = 0;
  for (size_t m = 0; m < 2; ++m) {
    const RenderMesh& ref = tubes[m == 0 ? 0 : 2];
    const TubeFromGlb t = read_tube(g, g.doc["meshes"][m], K, true);
    side_primitives += t.side_primitives;
    ASSERT_EQ(t.positions.size(), ref.mesh.vertices.size());
    for (size_t v = 0; v < t.positions.size(); ++v) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(t.positions[v][static_cast<size_t>(k)], static_cast<float>(ref.mesh.vertices[v][k])) << v;
        ASSERT_NEAR(t.normals[v][static_cast<size_t>(k)], ref.normals[v][k], 1e-6) << v;
      }
    }
    ASSERT_EQ(t.faces.size(), ref.mesh.faces.size());  // index count = 3 x triangles
    for (size_t f = 0; f < t.faces.size(); ++f) ASSERT_EQ(t.faces[f], ref.mesh.faces[f]) << f;
    const json& mat = g.doc["materials"][g.doc["meshes"][m]["primitives"][0]["material"].get<int>()];
    const RenderColour c = colours[m == 0 ? 0 : 2];
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(mat["pbrMetallicRoughness"]["baseColorFactor"][k].get<double>() * 255.0,
                  srgb_to_linear_byte(c[static_cast<size_t>(k)]), 0.5);
    }
  }
  EXPECT_GE(side_primitives, 3);  // the long yarn was split
}

// A ring of more than 32767 vertices cannot share a 16-bit primitive with
// the next ring: the tube is one primitive with 32-bit indices.
TEST(YarnGlb, HugeRingsUseIntIndices) {
  TempDir dir;
  YarnModel y;
  y.yarns.push_back({0, {{0, 0, 0}, {1, 0, 0}}, {0, 0}});
  TubeOptions o;
  o.plies = 1;
  o.vertices_per_ply = 40000;
  o.ring_spacing = 1.0;
  write_yarn_glb(dir.path("h.glb"), y, KnitParams{}, o);
  const Glb g = parse_glb(dir.read("h.glb"));
  const json& prims = g.doc["meshes"][0]["primitives"];
  ASSERT_EQ(prims.size(), 2u);  // side + caps
  for (size_t c = 0; c < 2; ++c) {
    const json& ia = g.doc["accessors"][prims[c]["indices"].get<int>()];
    EXPECT_EQ(ia["componentType"], 5125);
    const size_t nv =
        g.doc["accessors"][prims[c]["attributes"]["POSITION"].get<int>()]["count"].get<size_t>();
    EXPECT_EQ(nv, c == 0 ? 80000u : 80002u);
    EXPECT_EQ(ia["count"].get<size_t>(), 6u * 40000u);  // 2 K triangles either way
    const size_t io = accessor_offset(g, prims[c]["indices"].get<int>());
    uint32_t most = 0;
    for (size_t i = 0; i < ia["count"].get<size_t>(); ++i) most = std::max(most, u32(g.bin, io + 4 * i));
    EXPECT_EQ(most, nv - 1);
  }
}

TEST(YarnGlb, UncappedTubesAndErrors) {
  TempDir dir;
  YarnModel y;
  y.yarns.push_back({1, {{0, 0, 0}, {3, 1, 0}, {6, 0, 1}, {9, 2, 0}}, {0, 0, 0, 0}});
  TubeOptions o;
  o.capped = false;
  o.vertices_per_ply = 1;
  o.ring_spacing = 1.0;
  write_yarn_glb(dir.path("u.glb"), y, KnitParams{}, o);
  const Glb g = parse_glb(dir.read("u.glb"));
  const RenderMesh ref = yarn_tube(y.yarns[0].points, o, 0.12 * KnitParams{}.stitch_width, {});
  const TubeFromGlb t = read_tube(g, g.doc["meshes"][0], 6, false);
  ASSERT_EQ(t.faces.size(), ref.mesh.faces.size());
  for (size_t f = 0; f < t.faces.size(); ++f) EXPECT_EQ(t.faces[f], ref.mesh.faces[f]);

  YarnModel bad = y;
  bad.yarns.push_back({4, {{0, 0, 0}, {NAN, 1, 0}}, {0, 0}});
  const std::string msg = test::invalid_input([&] { write_yarn_glb(dir.path("b.glb"), bad, KnitParams{}); });
  EXPECT_CONTAINS(msg, "yarn 1 (id 4)");
  YarnModel none;
  none.yarns.push_back({0, {{1, 1, 1}, {1, 1, 1}}, {0, 0}});
  test::invalid_input([&] { write_yarn_glb(dir.path("n.glb"), none, KnitParams{}); });
  TubeOptions wrong;
  wrong.plies = 0;
  test::invalid_input([&] { write_yarn_glb(dir.path("w.glb"), y, KnitParams{}, wrong); });
  EXPECT_EQ(dir.num_files(), 1u);  // only u.glb
  test::io_error([&] { write_yarn_glb(dir.path("no/such/dir/x.glb"), y, KnitParams{}); });
}


TEST(AnimationGlb, MorphTargetsReproduceEveryFrame) {
  TempDir dir;
  const std::vector<double> times = {0.0, 0.5, 1.0};
  AnimatedMesh a;
  a.name = "garment";
  a.faces = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<Vec3> base = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 1}};
  for (int k = 0; k < 3; ++k) {
    std::vector<Vec3> f = base;
    for (size_t v = 0; v < f.size(); ++v) f[v] += Vec3(0.5 * k, -1.25 * k * v, 2.0 * k);
    a.frames.push_back(f);
  }
  AnimatedMesh b;
  b.name = "body";
  b.faces = {{0, 1, 2}};
  b.frames = {{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}, {{0, 0, -2}, {1, 0, -2}, {0, 1, -2}},
              {{0, 0, -3}, {1, 0, -3}, {0, 1, -3}}};
  write_animation_glb(dir.path("a.glb"), std::vector<AnimatedMesh>{a, b}, times);
  const Glb g = parse_glb(dir.read("a.glb"));
  ASSERT_EQ(g.doc["meshes"].size(), 2u);
  ASSERT_EQ(g.doc["animations"].size(), 1u);
  const json& anim = g.doc["animations"][0];
  ASSERT_EQ(anim["channels"].size(), 2u);
  for (size_t m = 0; m < 2; ++m) {
    const AnimatedMesh& src = m == 0 ? a : b;
    const json& prim = g.doc["meshes"][m]["primitives"][0];
    ASSERT_EQ(prim["targets"].size(), 2u);  // frames - 1
    EXPECT_EQ(g.doc["meshes"][m]["weights"].size(), 2u);
    const int pos = prim["attributes"]["POSITION"].get<int>();
    EXPECT_EQ(g.doc["accessors"][pos]["count"].get<size_t>(), src.frames[0].size());
    const int idx = prim["indices"].get<int>();
    EXPECT_EQ(g.doc["accessors"][idx]["count"].get<size_t>(), 3 * src.faces.size());
    // Frame k = base + target k-1 (the displacements), within float32.
    for (int k = 1; k < 3; ++k) {
      const int t = prim["targets"][k - 1]["POSITION"].get<int>();
      const size_t off = accessor_offset(g, t), base_off = accessor_offset(g, pos);
      const json& acc = g.doc["accessors"][t];
      for (size_t v = 0; v < src.frames[0].size(); ++v) {
        for (size_t c = 0; c < 3; ++c) {
          const float d = f32(g.bin, off + 12 * v + 4 * c), p0 = f32(g.bin, base_off + 12 * v + 4 * c);
          EXPECT_NEAR(p0 + d, src.frames[k][v][c], 1e-5);
          EXPECT_GE(d, acc["min"][c].get<float>());
          EXPECT_LE(d, acc["max"][c].get<float>());
        }
      }
    }
    // The sampler: the frame times in, one-hot weights out.
    const json& ch = anim["channels"][m];
    EXPECT_EQ(ch["target"]["node"].get<size_t>(), m);
    EXPECT_EQ(ch["target"]["path"], "weights");
    const json& sampler = anim["samplers"][ch["sampler"].get<int>()];
    EXPECT_EQ(sampler["interpolation"], "LINEAR");
    const int in = sampler["input"].get<int>(), out = sampler["output"].get<int>();
    ASSERT_EQ(g.doc["accessors"][in]["count"].get<size_t>(), 3u);
    ASSERT_EQ(g.doc["accessors"][out]["count"].get<size_t>(), 6u);  // frames x targets
    const size_t in_off = accessor_offset(g, in), out_off = accessor_offset(g, out);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_FLOAT_EQ(f32(g.bin, in_off + 4 * k), static_cast<float>(times[k]));
      for (size_t w = 0; w < 2; ++w) EXPECT_EQ(f32(g.bin, out_off + 4 * (2 * k + w)), k >= 1 && w == k - 1 ? 1.0f : 0.0f);
    }
  }
}

TEST(AnimationGlb, RefusesMismatchedFrames) {
  TempDir dir;
  AnimatedMesh a;
  a.faces = {{0, 1, 2}};
  a.frames = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 0}, {1, 0, 0}}};
  const std::vector<double> times = {0.0, 1.0};
  EXPECT_THROW(write_animation_glb(dir.path("a.glb"), std::vector<AnimatedMesh>{a}, times), InvalidInput);
  a.frames[1].push_back({0, 1, 0});
  const std::vector<double> bad_times = {1.0, 0.5};
  EXPECT_THROW(write_animation_glb(dir.path("a.glb"), std::vector<AnimatedMesh>{a}, bad_times), InvalidInput);
  a.faces = {{0, 1, 3}};
  EXPECT_THROW(write_animation_glb(dir.path("a.glb"), std::vector<AnimatedMesh>{a}, times), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(dir.path("a.glb")));
}

}  // namespace
}  // namespace knitforge
