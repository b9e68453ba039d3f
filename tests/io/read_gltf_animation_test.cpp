#include "knitforge/io/read_gltf_animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include <nlohmann/json.hpp>

#include "io/io_test_util.h"
#include "knitforge/io/gltf.h"

namespace knitforge {
namespace {

using nlohmann::json;
using test::TempDir;

void put_u32(std::string& s, uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}

/// A small glTF document and its buffer, built by hand.
struct Builder {
  json doc = {{"asset", {{"version", "2.0"}}}, {"buffers", json::array()}, {"bufferViews", json::array()},
              {"accessors", json::array()}};
  std::string bin;

  int view(const std::string& bytes) {
    while (bin.size() % 4) bin.push_back('\0');
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}});
    bin += bytes;
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const char* type, size_t width) {
    std::string b(4 * v.size(), '\0');
    std::memcpy(b.data(), v.data(), b.size());
    doc["accessors"].push_back(
        {{"bufferView", view(b)}, {"componentType", 5126}, {"count", v.size() / width}, {"type", type}});
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int u16(const std::vector<uint16_t>& v) {
    std::string b(2 * v.size(), '\0');
    std::memcpy(b.data(), v.data(), b.size());
    doc["accessors"].push_back({{"bufferView", view(b)}, {"componentType", 5123}, {"count", v.size()}, {"type", "SCALAR"}});
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  std::string glb() {
    json d = doc;
    while (bin.size() % 4) bin.push_back('\0');
    d["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string j = d.dump();
    while (j.size() % 4) j.push_back(' ');
    std::string out;
    put_u32(out, 0x46546C67);
    put_u32(out, 2);
    put_u32(out, static_cast<uint32_t>(12 + 8 + j.size() + 8 + bin.size()));
    put_u32(out, static_cast<uint32_t>(j.size()));
    put_u32(out, 0x4E4F534A);
    out += j;
    put_u32(out, static_cast<uint32_t>(bin.size()));
    put_u32(out, 0x004E4942);
    return out + bin;
  }
  std::string gltf_data_uri() const {
    static const char* a = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string e;
    for (size_t i = 0; i < bin.size(); i += 3) {
      uint32_t v = static_cast<uint8_t>(bin[i]) << 16;
      if (i + 1 < bin.size()) v |= static_cast<uint8_t>(bin[i + 1]) << 8;
      if (i + 2 < bin.size()) v |= static_cast<uint8_t>(bin[i + 2]);
      e += a[(v >> 18) & 63];
      e += a[(v >> 12) & 63];
      e += i + 1 < bin.size() ? a[(v >> 6) & 63] : '=';
      e += i + 2 < bin.size() ? a[v & 63] : '=';
    }
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + e}}});
    return d.dump();
  }
};

/// A triangle (0,0,0) (10,0,0) (0,10,0) on node 1, child of node 0; node 0
/// turns about z from 0 to 90 degrees over 1 s (LINEAR), node 1 moves up by
/// 5 at 0.5 s (STEP).
Builder rigid_triangle() {
  Builder b;
  const int pos = b.floats({0, 0, 0, 10, 0, 0, 0, 10, 0}, "VEC3", 3);
  const int idx = b.u16({0, 1, 2});
  const int times = b.floats({0.0f, 1.0f}, "SCALAR", 1);
  const float h = static_cast<float>(std::sqrt(0.5));
  const int rot = b.floats({0, 0, 0, 1, 0, 0, h, h}, "VEC4", 4);
  const int tt = b.floats({0.0f, 0.5f}, "SCALAR", 1);
  const int tv = b.floats({0, 0, 0, 0, 0, 5}, "VEC3", 3);
  b.doc["meshes"] = {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}}};
  b.doc["nodes"] = {{{"name", "root"}, {"children", {1}}, {"translation", {100, 0, 0}}},
                    {{"name", "leaf"}, {"mesh", 0}}};
  b.doc["scenes"] = {{{"nodes", {0}}}};
  b.doc["animations"] = {{{"name", "turn"},
                          {"samplers",
                           {{{"input", times}, {"output", rot}},
                            {{"input", tt}, {"output", tv}, {"interpolation", "STEP"}}}},
                          {"channels",
                           {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}},
                            {{"sampler", 1}, {"target", {{"node", 1}, {"path", "translation"}}}}}}}};
  return b;
}

/// A skinned strip along x (0 to 20 mm at x = 0, 5, ..., 20; y = 0 and 2):
/// joint 0 "shoulder" at the origin, joint 1 "elbow" its child at x = 10
/// (inverse bind matrix: back by 10); vertices left of x = 10 follow the
/// shoulder, right of it the elbow, at x = 10 half each (8-bit normalised
/// weights: 127/255 the shoulder, 128/255 the elbow). The elbow turns about z from 0 to 90
/// degrees over 1 s. The mesh node has a translation the specification says
/// to ignore.
Builder skinned_strip() {
  Builder b;
  std::vector<float> pos;
  std::vector<uint16_t> idx;
  std::string joints, weights;
  for (int i = 0; i < 5; ++i) {
    for (int r = 0; r < 2; ++r) {
      pos.insert(pos.end(), {5.0f * i, 2.0f * r, 0.0f});
      const int j0 = i <= 2 ? 0 : 1, j1 = i == 2 ? 1 : 0;  // x = 10: shoulder and elbow
      const uint8_t w0 = i == 2 ? 127 : 255, w1 = i == 2 ? 128 : 0;
      joints += std::string{static_cast<char>(j0), static_cast<char>(j1), 0, 0};
      weights += std::string{static_cast<char>(w0), static_cast<char>(w1), 0, 0};
    }
    if (i > 0) {
      const uint16_t a = static_cast<uint16_t>(2 * i - 2);
      idx.insert(idx.end(), {a, static_cast<uint16_t>(a + 2), static_cast<uint16_t>(a + 1),
                             static_cast<uint16_t>(a + 1), static_cast<uint16_t>(a + 2), static_cast<uint16_t>(a + 3)});
    }
  }
  const int p = b.floats(pos, "VEC3", 3);
  const int ix = b.u16(idx);
  b.doc["accessors"].push_back({{"bufferView", b.view(joints)}, {"componentType", 5121}, {"count", 10}, {"type", "VEC4"}});
  const int ja = static_cast<int>(b.doc["accessors"].size()) - 1;
  b.doc["accessors"].push_back(
      {{"bufferView", b.view(weights)}, {"componentType", 5121}, {"normalized", true}, {"count", 10}, {"type", "VEC4"}});
  const int wa = static_cast<int>(b.doc["accessors"].size()) - 1;
  std::vector<float> ibm(32, 0.0f);
  for (int m = 0; m < 2; ++m)
    for (int k = 0; k < 4; ++k) ibm[static_cast<size_t>(16 * m + 5 * k)] = 1.0f;
  ibm[16 + 12] = -10.0f;  // column-major: the translation is entries 12-14
  const int ib = b.floats(ibm, "MAT4", 16);
  const int times = b.floats({0.0f, 1.0f}, "SCALAR", 1);
  const float h = static_cast<float>(std::sqrt(0.5));
  const int rot = b.floats({0, 0, 0, 1, 0, 0, h, h}, "VEC4", 4);
  b.doc["meshes"] = {{{"name", "arm"},
                      {"primitives",
                       {{{"attributes", {{"POSITION", p}, {"JOINTS_0", ja}, {"WEIGHTS_0", wa}}}, {"indices", ix}}}}}};
  b.doc["nodes"] = {{{"name", "shoulder"}, {"children", {1}}},
                    {{"name", "elbow"}, {"translation", {10, 0, 0}}},
                    {{"name", "skinned"}, {"mesh", 0}, {"skin", 0}, {"translation", {1000, 0, 0}}}};
  b.doc["skins"] = {{{"joints", {0, 1}}, {"inverseBindMatrices", ib}}};
  b.doc["scenes"] = {{{"nodes", {0, 2}}}};
  b.doc["animations"] = {{{"name", "bend"},
                          {"samplers", {{{"input", times}, {"output", rot}}}},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}};
  return b;
}

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-5) {
  EXPECT_NEAR((a - b).norm(), 0.0, tol) << a.transpose() << " vs " << b.transpose();
}

template <class E, class F>
void expect_error(F&& f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const E& e) {
    for (const char* p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

TEST(ReadGltfAnimation, OurAnimationGlbReadsBackFrameForFrame) {
  TempDir dir;
  std::vector<AnimatedMesh> meshes(2);
  meshes[0].name = "garment";
  meshes[0].faces = {{0, 1, 2}, {0, 2, 3}};
  meshes[1].name = "body";
  meshes[1].faces = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {0, 2, 3}};
  const std::vector<double> times = {0.0, 1.0 / 30, 2.0 / 30, 3.0 / 30};
  for (size_t k = 0; k < times.size(); ++k) {
    const double a = 0.3 * static_cast<double>(k);
    meshes[0].frames.push_back({{0, 0, 5}, {10, 0, 5 + a}, {10, 10, 5}, {0, 10, 5 - a}});
    meshes[1].frames.push_back(
        {{0, 0, 0}, {20 * std::cos(a), 20 * std::sin(a), 0}, {0, 20, 1.5 * a}, {3, 3, -10 - a}});
  }
  write_animation_glb(dir.path("animation.glb"), meshes, times);

  GltfReadOptions o;
  o.mesh_name = "body";
  const GltfAnimatedMesh m = read_gltf_animation(dir.path("animation.glb"), o);
  EXPECT_EQ(m.faces, meshes[1].faces);
  EXPECT_EQ(m.num_vertices, 4);
  EXPECT_EQ(m.animation_name, "motion");
  EXPECT_DOUBLE_EQ(m.start_s, 0.0);
  EXPECT_NEAR(m.end_s, 0.1, 1e-7);
  for (size_t k = 0; k < times.size(); ++k) {
    const std::vector<Vec3> p = gltf_positions_at(m, times[k]);
    ASSERT_EQ(p.size(), 4u);
    for (size_t v = 0; v < 4; ++v) expect_near(p[v], meshes[1].frames[k][v]);
  }
  // Between two frames: linear.
  const std::vector<Vec3> mid = gltf_positions_at(m, 0.5 * (times[1] + times[2]));
  for (size_t v = 0; v < 4; ++v) expect_near(mid[v], 0.5 * (meshes[1].frames[1][v] + meshes[1].frames[2][v]));
  // Past the end: the last frame.
  expect_near(gltf_positions_at(m, 10.0)[1], meshes[1].frames[3][1]);

  // Every mesh: the two together, garment first.
  const GltfAnimatedMesh both = read_gltf_animation(dir.path("animation.glb"));
  EXPECT_EQ(both.num_vertices, 8);
  EXPECT_EQ(both.faces.size(), 6u);
  expect_near(gltf_positions_at(both, times[3])[5], meshes[1].frames[3][1]);
}

TEST(ReadGltfAnimation, RigidNodeMotionThroughTheHierarchy) {
  TempDir dir;
  Builder b = rigid_triangle();
  for (const std::string& file : {dir.write("r.glb", b.glb()), dir.write("r.gltf", b.gltf_data_uri())}) {
    const GltfAnimatedMesh m = read_gltf_animation(file);
    EXPECT_EQ(m.animation_name, "turn");
    EXPECT_EQ(m.num_vertices, 3);
    EXPECT_DOUBLE_EQ(m.end_s, 1.0);
    std::vector<Vec3> p = gltf_positions_at(m, 0.0);
    expect_near(p[1], Vec3(110, 0, 0));
    p = gltf_positions_at(m, 0.25);  // 22.5 degrees (slerp), before the step
    const double a = M_PI / 8;
    expect_near(p[1], Vec3(100 + 10 * std::cos(a), 10 * std::sin(a), 0));
    p = gltf_positions_at(m, 1.0);  // 90 degrees, 5 up
    expect_near(p[1], Vec3(100, 10, 5));
    expect_near(p[2], Vec3(90, 0, 5));
  }
  // External buffer file next to the .gltf.
  json d = json::parse(b.gltf_data_uri());
  d["buffers"][0]["uri"] = "my%20data.bin";
  dir.write("my data.bin", b.bin);
  const GltfAnimatedMesh m = read_gltf_animation(dir.write("ext.gltf", d.dump()));
  expect_near(gltf_positions_at(m, 1.0)[2], Vec3(90, 0, 5));
}

TEST(ReadGltfAnimation, StripsSparseTargetsCubicSplinesAndSeams) {
  TempDir dir;
  Builder b;
  // A strip of 2 triangles; vertex 4 duplicates vertex 1 (a seam), used by none.
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 1, 0, 0}, "VEC3", 3);
  const int idx = b.u16({0, 1, 2, 3});
  // A sparse morph target: vertex 3 moves +2 z.
  const int sidx = b.view(std::string("\x03\x00", 2));
  std::string sv(12, '\0');
  const float dz[3] = {0, 0, 2};
  std::memcpy(sv.data(), dz, 12);
  const int sval = b.view(sv);
  b.doc["accessors"].push_back({{"componentType", 5126},
                                {"count", 5},
                                {"type", "VEC3"},
                                {"sparse",
                                 {{"count", 1},
                                  {"indices", {{"bufferView", sidx}, {"componentType", 5123}}},
                                  {"values", {{"bufferView", sval}}}}}});
  const int target = static_cast<int>(b.doc["accessors"].size()) - 1;
  const int t = b.floats({0, 2}, "SCALAR", 1);
  // Cubic spline weights: (in, value, out) per key: 0 -> 1 with zero tangents.
  const int w = b.floats({0, 0, 0, 0, 1, 0}, "SCALAR", 1);
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"mode", 5},
                                       {"targets", {{{"POSITION", target}}}}}}}}};
  b.doc["nodes"] = {{{"mesh", 0}}};
  b.doc["animations"] = {{{"samplers", {{{"input", t}, {"output", w}, {"interpolation", "CUBICSPLINE"}}}},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}}};
  const GltfAnimatedMesh m = read_gltf_animation(dir.write("s.glb", b.glb()));
  EXPECT_EQ(m.num_vertices, 4);  // the seam's copy merged
  ASSERT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.animation_name, "#0");
  // Smoothstep at the middle: weight 0.5.
  expect_near(gltf_positions_at(m, 1.0)[3], Vec3(1, 1, 1));
  expect_near(gltf_positions_at(m, 2.0)[3], Vec3(1, 1, 2));
  expect_near(gltf_positions_at(m, 0.0)[3], Vec3(1, 1, 0));
}

// Linear blend skinning: the bind pose at t = 0 (the joints' global
// transforms cancel their inverse bind matrices), the elbow's side turned
// about the elbow at 1 s, the vertices weighted half and half in between,
// and the skinned node's own translation ignored.
TEST(ReadGltfAnimation, SkinnedMeshFollowsItsJoints) {
  TempDir dir;
  const Builder b = skinned_strip();
  const GltfAnimatedMesh m = read_gltf_animation(dir.write("arm.glb", Builder(b).glb()));
  EXPECT_EQ(m.num_vertices, 10);
  EXPECT_EQ(m.faces.size(), 8u);
  ASSERT_EQ(m.skins.size(), 1u);
  const std::vector<Vec3> rest = gltf_positions_at(m, 0.0);
  for (int i = 0; i < 5; ++i)
    for (int r = 0; r < 2; ++r) expect_near(rest[static_cast<size_t>(2 * i + r)], Vec3(5.0 * i, 2.0 * r, 0));
  const std::vector<Vec3> bent = gltf_positions_at(m, 1.0);
  for (int r = 0; r < 2; ++r) {
    const double y = 2.0 * r;
    expect_near(bent[static_cast<size_t>(r)], Vec3(0, y, 0));           // shoulder's
    expect_near(bent[static_cast<size_t>(2 + r)], Vec3(5, y, 0));       // shoulder's
    expect_near(bent[static_cast<size_t>(8 + r)], Vec3(10 - y, 10, 0)); // the elbow's, turned 90 degrees
    expect_near(bent[static_cast<size_t>(6 + r)], Vec3(10 - y, 5, 0));
    // Half each (127/255 and 128/255, summing to 1): between (10, y) and (10 - y, 0).
    const double w1 = 128.0 / 255.0;
    expect_near(bent[static_cast<size_t>(4 + r)], Vec3(10 - w1 * y, (1 - w1) * y, 0), 1e-6);
  }
  // Halfway: the elbow's tip on the 45-degree line from the elbow.
  const double c = std::sqrt(0.5);
  expect_near(gltf_positions_at(m, 0.5)[8], Vec3(10 + 10 * c, 10 * c, 0));
  // The same from a .gltf with the buffer in a data: URI.
  const GltfAnimatedMesh u = read_gltf_animation(dir.write("arm.gltf", b.gltf_data_uri()));
  expect_near(gltf_positions_at(u, 1.0)[9], Vec3(8, 10, 0));
}

TEST(ReadGltfAnimation, BadSkinsAreRefusedNamingTheElement) {
  TempDir dir;
  auto with = [&](const std::function<void(Builder&)>& edit) {
    Builder b = skinned_strip();
    edit(b);
    return dir.write("bad_skin.glb", b.glb());
  };
  expect_error<IOError>([&] { read_gltf_animation(with([](Builder& b) { b.doc["skins"][0]["joints"] = {0, 7}; })); },
                        {"bad_skin.glb", "skins[0]", "joint 7 is not a node index"});
  expect_error<IOError>([&] { read_gltf_animation(with([](Builder& b) { b.doc["skins"][0]["joints"] = {0}; })); },
                        {"meshes[0].primitives[0]", "JOINTS_0", "uses joint 1", "1 joints"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"].erase("JOINTS_0"); }));
      },
      {"meshes[0].primitives[0]", "WEIGHTS_0 without JOINTS_0"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) {
          auto& a = b.doc["meshes"][0]["primitives"][0]["attributes"];
          a.erase("JOINTS_0");
          a.erase("WEIGHTS_0");
        }));
      },
      {"meshes[0].primitives[0]", "skinned node but has no JOINTS_0"});
  expect_error<IOError>(  // weights not normalised: 128/255 alone at x = 10
      [&] {
        read_gltf_animation(with([](Builder& b) {
          std::string w(40, '\0');
          for (int v = 0; v < 10; ++v) w[static_cast<size_t>(4 * v)] = static_cast<char>(v / 2 == 2 ? 128 : 255);
          b.doc["accessors"].push_back({{"bufferView", b.view(w)}, {"componentType", 5121}, {"normalized", true},
                                        {"count", 10}, {"type", "VEC4"}});
          b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = b.doc["accessors"].size() - 1;
        }));
      },
      {"skin weights of vertex 4 sum to 0.502", "normalised"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) {
          std::vector<float> m(32, 0.0f);
          b.doc["skins"][0]["inverseBindMatrices"] = b.floats(m, "MAT4", 16);
        }));
      },
      {"skins[0]", "inverse bind matrix 0", "(0, 0, 0, 1)"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) {
          b.doc["skins"][0]["inverseBindMatrices"] = b.floats(std::vector<float>(16, 0.0f), "MAT4", 16);
        }));
      },
      {"skins[0]", "1 matrices for 2 joints"});
  expect_error<IOError>([&] { read_gltf_animation(with([](Builder& b) { b.doc["nodes"][2]["skin"] = 3; })); },
                        {"nodes[2]", "refers to skins[3]"});
}

TEST(ReadGltfAnimation, BadFilesAreRefusedNamingTheElement) {
  TempDir dir;
  expect_error<IOError>([&] { read_gltf_animation(dir.write("j.gltf", "{not json")); }, {"j.gltf", "not a glTF"});
  expect_error<IOError>([&] { read_gltf_animation(dir.path("none.glb")); }, {"none.glb"});
  {
    std::string g = rigid_triangle().glb();
    expect_error<IOError>([&] { read_gltf_animation(dir.write("cut.glb", g.substr(0, g.size() - 9))); },
                          {"cut.glb", "the file has"});
    g[4] = 1;
    expect_error<IOError>([&] { read_gltf_animation(dir.write("v1.glb", g)); }, {"version 1"});
  }
  auto with = [&](const std::function<void(Builder&)>& edit) {
    Builder b = rigid_triangle();
    edit(b);
    return dir.write("bad.glb", b.glb());
  };
  expect_error<IOError>([&] { read_gltf_animation(with([](Builder& b) { b.doc["accessors"][0]["count"] = 4; })); },
                        {"bad.glb", "accessors[0] (POSITION of meshes[0].primitives[0])", "do not fit"});
  expect_error<IOError>(
      [&] { read_gltf_animation(with([](Builder& b) { b.doc["accessors"][0]["componentType"] = 5123; })); },
      {"accessors[0]", "componentType is 5123"});
  expect_error<IOError>(
      [&] { read_gltf_animation(with([](Builder& b) { b.doc["bufferViews"][1]["byteOffset"] = 1000000; })); },
      {"bufferViews[1]", "outside buffers[0]"});
  expect_error<IOError>(
      [&] { read_gltf_animation(with([](Builder& b) { b.doc["meshes"][0]["primitives"][0]["indices"] = 42; })); },
      {"refers to accessors[42]"});
  expect_error<IOError>(
      [&] { read_gltf_animation(with([](Builder& b) { b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"}; })); },
      {"KHR_draco_mesh_compression"});
  expect_error<IOError>([&] { read_gltf_animation(with([](Builder& b) { b.doc["nodes"][1]["children"] = {0}; })); },
                        {"cycle"});
  expect_error<IOError>(
      [&] { read_gltf_animation(with([](Builder& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 1; })); },
      {"meshes[0].primitives[0]", "mode 1"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) {
          b.doc["animations"][0]["samplers"][0]["input"] = b.floats({1.0f, 1.0f}, "SCALAR", 1);
        }));
      },
      {"animations[0].samplers[0]", "increase strictly"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) {
          b.doc["meshes"][0]["primitives"][0]["indices"] = b.u16({0, 1, 7});
        }));
      },
      {"index 7 is out of range"});
  expect_error<IOError>(
      [&] {
        read_gltf_animation(with([](Builder& b) {
          b.doc["animations"][0]["samplers"][0]["output"] = b.floats({0, 0, 0}, "VEC3", 3);
        }));
      },
      {"type is 'VEC3', it must be VEC4"});
  expect_error<IOError>(
      [&] {
        Builder b = rigid_triangle();
        json d = json::parse(b.gltf_data_uri());
        d["buffers"][0]["uri"] = "/etc/hostname";
        read_gltf_animation(dir.write("abs.gltf", d.dump()));
      },
      {"abs.gltf", "buffers[0]", "not a relative file name"});
  // Choices that name nothing in the file.
  const std::string ok = dir.write("ok.glb", rigid_triangle().glb());
  GltfReadOptions o;
  o.mesh_name = "arm";
  expect_error<InvalidInput>([&] { read_gltf_animation(ok, o); }, {"'arm'", "'leaf', 'tri'"});
  o = {};
  o.animation = "walk";
  expect_error<InvalidInput>([&] { read_gltf_animation(ok, o); }, {"'walk'", "'turn'"});
  expect_error<InvalidInput>(
      [&] {
        read_gltf_animation(with([](Builder& b) { b.doc["animations"].push_back(b.doc["animations"][0]); }));
      },
      {"2 animations", "animation_name"});
}

TEST(ReadGltfAnimation, FuzzSeedsRead) {
  // fuzz/make_gltf_seeds.py: Python's writer, not ours.
  const std::string seeds = std::string(KNITFORGE_TESTS_DIR) + "/../fuzz/corpus/fuzz_gltf_animation/";
  const GltfAnimatedMesh morph = read_gltf_animation(seeds + "morph_targets.glb");
  ASSERT_EQ(morph.num_vertices, 4);
  expect_near(gltf_positions_at(morph, 1.0 / 30)[3], Vec3(10, 10, 5));
  expect_near(gltf_positions_at(morph, 2.0 / 30)[3], Vec3(14, 10, 1));
  const GltfAnimatedMesh uri = read_gltf_animation(seeds + "morph_targets_data_uri.gltf");
  expect_near(gltf_positions_at(uri, 1.5 / 30)[3], Vec3(12, 10, 3));
  const GltfAnimatedMesh rigid = read_gltf_animation(seeds + "rigid_hierarchy.glb");
  EXPECT_EQ(rigid.num_vertices, 8);  // the strip twice: under "root" and as "other"
  // At 1 s: root turned 90 degrees (normalised shorts), leaf 5 up, the target at weight 0 for leaf.
  expect_near(gltf_positions_at(rigid, 1.0)[1], Vec3(100, 1, 5), 1e-3);
  // "other": a static matrix (+5, +6, +7), its target at weight 0.5 at 1 s.
  expect_near(gltf_positions_at(rigid, 1.0)[7], Vec3(6, 7, 8), 1e-6);
  // Skinned: at 1 s the hips moved 10 along x and the spine (joint 0) turned
  // 90 degrees about z around (10, 0, 1); vertex 3 is half each (0.25 + 0.25
  // in two sets), vertex 1 the hips' only; the node's translation ignored.
  const GltfAnimatedMesh skinned = read_gltf_animation(seeds + "skinned.glb");
  ASSERT_EQ(skinned.num_vertices, 4);
  expect_near(gltf_positions_at(skinned, 0.0)[3], Vec3(1, 1, 0), 1e-6);
  expect_near(gltf_positions_at(skinned, 1.0)[1], Vec3(11, 0, 0), 1e-6);
  expect_near(gltf_positions_at(skinned, 1.0)[3], Vec3(10, 1, 0), 1e-6);
}

}  // namespace
}  // namespace knitforge
