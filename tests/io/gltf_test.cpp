#include "knitforge/io/gltf.h"

#include <gtest/gtest.h>

#include <cstring>

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

size_t component_size(int type) { return type == 5126 || type == 5125 ? 4 : type == 5121 ? 1 : 0; }
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

}  // namespace
}  // namespace knitforge
