#pragma once
// A tiny synthetic body model in SMPL's npz format (SMPL's axes: metres, y
// up, facing +z, left side +x) for the tests of load_smpl_model() and of
// `body make/fit --model`: a closed tube 1.6 m tall of rings of 8 vertices,
// a nose bulge on the front (+z) near the top, SMPL's 24-joint tree with
// joints regressed from rings (left joints from the +x side of a ring),
// weights blending joints along the spine and, at the sides, the hips and
// shoulders; 3 shape directions and pose-corrective directions with
// arbitrary deterministic values. Written by the tests themselves: no SMPL
// data is used or shipped.

#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "io/npz_test_writer.h"

namespace knitforge::test {

/// The arrays of an SMPL model file, in the file's layout (C order).
struct SmplArrays {
  int V = 0, F = 0, K = 3, J = 24;
  std::vector<double> v_template;   // V x 3
  std::vector<int64_t> f;           // F x 3
  std::vector<double> shapedirs;    // V x 3 x K
  std::vector<double> posedirs;     // V x 3 x 9(J-1)
  std::vector<double> J_regressor;  // J x V
  std::vector<int64_t> kintree;     // 2 x J
  std::vector<double> weights;      // V x J

  int P() const { return 9 * (J - 1); }
  double& w(int v, int j) { return weights[static_cast<size_t>(v * J + j)]; }

  /// Every array as .npy bytes, by key.
  std::map<std::string, std::string> npy() const {
    std::map<std::string, std::string> m;
    m["v_template"] = npy_f8({V, 3}, v_template);
    m["f"] = npy_bytes("<u4", {F, 3}, raw_bytes<uint32_t>(f));
    m["shapedirs"] = npy_f8({V, 3, K}, shapedirs);
    m["posedirs"] = npy_f8({V, 3, P()}, posedirs);
    m["J_regressor"] = npy_f8({J, V}, J_regressor);
    m["kintree_table"] = npy_i8({2, J}, kintree);
    m["weights"] = npy_f8({V, J}, weights);
    return m;
  }
};

inline const std::vector<int>& smpl_test_parents() {
  static const std::vector<int> p = {-1, 0, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};
  return p;
}

inline SmplArrays smpl_test_arrays() {
  SmplArrays a;
  const int rings = 9, per = 8;
  const double radius = 0.15, step = 0.2;
  auto ring_vertex = [&](int r, int s) { return r * per + (s % per); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < per; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / per;
      const double bulge = (r == 7 && s == 2) ? 0.06 : 0.0;  // the nose, at +z
      a.v_template.insert(a.v_template.end(),
                          {(radius + bulge) * std::cos(phi), step * r, (radius + bulge) * std::sin(phi)});
    }
  }
  const int bottom = rings * per, top = bottom + 1;
  a.v_template.insert(a.v_template.end(), {0.0, -0.05, 0.0, 0.0, step * (rings - 1) + 0.08, 0.0});
  a.V = top + 1;
  for (int r = 0; r + 1 < rings; ++r) {
    for (int s = 0; s < per; ++s) {
      a.f.insert(a.f.end(), {ring_vertex(r, s), ring_vertex(r + 1, s), ring_vertex(r + 1, s + 1)});
      a.f.insert(a.f.end(), {ring_vertex(r, s), ring_vertex(r + 1, s + 1), ring_vertex(r, s + 1)});
    }
  }
  for (int s = 0; s < per; ++s) {
    a.f.insert(a.f.end(), {bottom, ring_vertex(0, s), ring_vertex(0, s + 1)});
    a.f.insert(a.f.end(), {top, ring_vertex(rings - 1, s + 1), ring_vertex(rings - 1, s)});
  }
  a.F = static_cast<int>(a.f.size() / 3);

  // Shapes: 0 widens (+20 mm radius per unit), 1 stretches upwards, 2 arbitrary.
  a.shapedirs.assign(static_cast<size_t>(a.V * 3 * a.K), 0.0);
  for (int v = 0; v < a.V; ++v) {
    const double x = a.v_template[static_cast<size_t>(3 * v)], y = a.v_template[static_cast<size_t>(3 * v + 1)],
                 z = a.v_template[static_cast<size_t>(3 * v + 2)];
    auto sd = [&](int d, int k) -> double& { return a.shapedirs[static_cast<size_t>((3 * v + d) * a.K + k)]; };
    sd(0, 0) = x / radius * 0.02;
    sd(2, 0) = z / radius * 0.02;
    sd(1, 1) = 0.05 * y / 1.6;
    for (int d = 0; d < 3; ++d) sd(d, 2) = 0.004 * std::sin(1.7 * v + 2.3 * d);
  }
  a.posedirs.resize(static_cast<size_t>(a.V * 3 * a.P()));
  for (size_t i = 0; i < a.posedirs.size(); ++i) a.posedirs[i] = 0.002 * std::sin(0.37 * static_cast<double>(i) + 1.1);

  // Joints: the ring each regresses from; side: +1 the ring's +x vertices,
  // -1 its -x ones, 0 all of them.
  const int ring_of[24] = {4, 3, 3, 5, 2, 2, 5, 1, 1, 6, 0, 0, 7, 6, 6, 8, 7, 7, 7, 7, 7, 7, 7, 7};
  const int side_of[24] = {0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 0, 1, -1, 1, -1, 1, -1, 1, -1};
  a.J_regressor.assign(static_cast<size_t>(a.J * a.V), 0.0);
  for (int j = 0; j < a.J; ++j) {
    std::vector<int> from;
    for (int s = 0; s < per; ++s) {
      const double c = std::cos(2.0 * std::numbers::pi * s / per);
      if (side_of[j] == 0 || (side_of[j] > 0 ? c > 0.1 : c < -0.1)) from.push_back(ring_vertex(ring_of[j], s));
    }
    for (int v : from) a.J_regressor[static_cast<size_t>(j * a.V + v)] = 1.0 / static_cast<double>(from.size());
  }
  a.kintree.assign(static_cast<size_t>(2 * a.J), 0);
  for (int j = 0; j < a.J; ++j) {
    a.kintree[static_cast<size_t>(j)] = j == 0 ? 4294967295LL : smpl_test_parents()[static_cast<size_t>(j)];
    a.kintree[static_cast<size_t>(a.J + j)] = j;
  }
  // Weights: the spine joint of the ring and the next one up; the sides of
  // rings 2-3 also follow the hips, of ring 7 the shoulders.
  const int spine[rings + 1] = {0, 0, 0, 0, 0, 3, 6, 9, 12, 15};
  a.weights.assign(static_cast<size_t>(a.V * a.J), 0.0);
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < per; ++s) {
      const int v = ring_vertex(r, s);
      const double c = std::cos(2.0 * std::numbers::pi * s / per);
      int side = -1;
      if (r == 2 || r == 3) side = c > 0.1 ? 1 : (c < -0.1 ? 2 : -1);
      if (r == 7) side = c > 0.1 ? 16 : (c < -0.1 ? 17 : -1);
      const double share = side >= 0 ? 0.4 : 0.0;
      a.w(v, spine[r]) += 0.7 * (1.0 - share);
      a.w(v, spine[r + 1]) += 0.3 * (1.0 - share);
      if (side >= 0) a.w(v, side) += share;
    }
  }
  a.w(bottom, 0) = 1.0;
  a.w(top, 15) = 1.0;
  return a;
}

/// The model as an .npz archive, entries alternately stored and deflated,
/// with `replace` swapping in other bytes for some keys (a missing key is
/// given as the empty string: left out).
inline std::string smpl_test_npz(const SmplArrays& a, const std::map<std::string, std::string>& replace = {}) {
  std::vector<ZipEntry> entries;
  bool deflate = false;
  for (auto& [key, bytes] : a.npy()) {
    const auto it = replace.find(key);
    if (it != replace.end() && it->second.empty()) continue;
    entries.push_back({key + ".npy", it != replace.end() ? it->second : bytes, deflate});
    deflate = !deflate;
  }
  // An array the loader does not read (SMPL files have strings too).
  entries.push_back({"bs_style.npy", npy_bytes("<U3", {}, std::string(12, '\0')), false});
  return zip_bytes(entries);
}

}  // namespace knitforge::test
