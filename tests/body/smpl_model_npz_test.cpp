// load_smpl_model(): a synthetic model in SMPL's npz format, written by the
// test, loaded, converted (metres -> mm, y up/facing +z -> z up/facing -y),
// posed against a hand-written SMPL forward pass, and every malformed file
// refused with the entry named.
#include "knitforge/body/smpl_model_npz.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "body/smpl_test_model.h"
#include "io/io_test_util.h"
#include "knitforge/body/body_pose.h"
#include "knitforge/body/skin_body.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

Vec3 at3(const std::vector<double>& a, int i) {
  return {a[static_cast<size_t>(3 * i)], a[static_cast<size_t>(3 * i + 1)], a[static_cast<size_t>(3 * i + 2)]};
}

double signed_volume(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& faces) {
  double s = 0.0;
  for (const auto& f : faces) s += v[static_cast<size_t>(f[0])].dot(v[static_cast<size_t>(f[1])].cross(v[static_cast<size_t>(f[2])]));
  return s / 6.0;
}

// SMPL's forward pass as its paper writes it, in SMPL's own frame and units
// (metres): shape, joints, pose feature, pose correctives, world transforms
// G_j, skinning with G_j [I, -J_j]. Independent of skin_body.cpp.
std::vector<Vec3> smpl_forward(const SmplArrays& a, const Eigen::VectorXd& beta, const std::vector<Vec3>& theta,
                               const Vec3& trans) {
  std::vector<Vec3> v(static_cast<size_t>(a.V));
  for (int i = 0; i < a.V; ++i) {
    v[static_cast<size_t>(i)] = at3(a.v_template, i);
    for (int k = 0; k < a.K; ++k)
      for (int d = 0; d < 3; ++d)
        v[static_cast<size_t>(i)][d] += a.shapedirs[static_cast<size_t>((3 * i + d) * a.K + k)] * beta(k);
  }
  std::vector<Vec3> J(static_cast<size_t>(a.J), Vec3::Zero());
  for (int j = 0; j < a.J; ++j)
    for (int i = 0; i < a.V; ++i) J[static_cast<size_t>(j)] += a.J_regressor[static_cast<size_t>(j * a.V + i)] * v[static_cast<size_t>(i)];
  std::vector<Mat3> R(static_cast<size_t>(a.J));
  for (int j = 0; j < a.J; ++j) {
    const Vec3& w = theta[static_cast<size_t>(j)];
    R[static_cast<size_t>(j)] = w.norm() > 0 ? Mat3(Eigen::AngleAxisd(w.norm(), w.normalized())) : Mat3::Identity();
  }
  std::vector<double> feature;
  for (int j = 1; j < a.J; ++j)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) feature.push_back(R[static_cast<size_t>(j)](r, c) - (r == c ? 1.0 : 0.0));
  for (int i = 0; i < a.V; ++i)
    for (int d = 0; d < 3; ++d)
      for (int p = 0; p < a.P(); ++p)
        v[static_cast<size_t>(i)][d] += a.posedirs[static_cast<size_t>((3 * i + d) * a.P() + p)] * feature[static_cast<size_t>(p)];
  std::vector<Eigen::Matrix4d> G(static_cast<size_t>(a.J));
  for (int j = 0; j < a.J; ++j) {
    Eigen::Matrix4d local = Eigen::Matrix4d::Identity();
    local.topLeftCorner<3, 3>() = R[static_cast<size_t>(j)];
    const int p = smpl_test_parents()[static_cast<size_t>(j)];
    local.topRightCorner<3, 1>() = p < 0 ? J[0] : Vec3(J[static_cast<size_t>(j)] - J[static_cast<size_t>(p)]);
    G[static_cast<size_t>(j)] = p < 0 ? local : Eigen::Matrix4d(G[static_cast<size_t>(p)] * local);
  }
  std::vector<Vec3> out(static_cast<size_t>(a.V));
  for (int i = 0; i < a.V; ++i) {
    Eigen::Matrix4d T = Eigen::Matrix4d::Zero();
    for (int j = 0; j < a.J; ++j) {
      Eigen::Matrix4d rest = Eigen::Matrix4d::Identity();
      rest.topRightCorner<3, 1>() = -J[static_cast<size_t>(j)];
      T += a.weights[static_cast<size_t>(i * a.J + j)] * G[static_cast<size_t>(j)] * rest;
    }
    out[static_cast<size_t>(i)] = (T * v[static_cast<size_t>(i)].homogeneous()).head<3>() + trans;
  }
  return out;
}

std::string refused(const TempDir& dir, const SmplArrays& a, const std::map<std::string, std::string>& replace = {}) {
  const std::string p = dir.write("bad.npz", smpl_test_npz(a, replace));
  return io_error([&] { load_smpl_model(p); });
}

}  // namespace

TEST(SmplModelNpz, ConvertsUnitsAndAxes) {
  TempDir dir;
  const SmplArrays a = smpl_test_arrays();
  const BodyModel m = load_smpl_model(dir.write("tiny_smpl.npz", smpl_test_npz(a)));
  EXPECT_EQ(m.name, "tiny_smpl.npz");
  ASSERT_EQ(m.num_vertices(), a.V);
  ASSERT_EQ(m.num_faces(), a.F);
  ASSERT_EQ(m.num_joints(), 24);
  ASSERT_EQ(m.num_shapes(), 3);
  EXPECT_EQ(m.shape_names, (std::vector<std::string>{"beta0", "beta1", "beta2"}));
  EXPECT_EQ(m.joint_names, smpl_joint_names());
  EXPECT_EQ(m.parents, smpl_test_parents());
  EXPECT_TRUE(m.vertex_parts.empty());
  EXPECT_TRUE(m.landmarks.empty());
  for (int i = 0; i < a.V; ++i) {
    const Vec3 s = at3(a.v_template, i);
    EXPECT_NEAR((m.template_vertices[static_cast<size_t>(i)] - 1000.0 * Vec3(s.x(), -s.z(), s.y())).norm(), 0.0, 1e-9);
    for (int k = 0; k < 3; ++k) {
      auto sd = [&](int d) { return a.shapedirs[static_cast<size_t>((3 * i + d) * a.K + k)]; };
      EXPECT_NEAR((m.shape_basis.block<3, 1>(3 * i, k) - 1000.0 * Vec3(sd(0), -sd(2), sd(1))).norm(), 0.0, 1e-9);
    }
  }
  // The head (top cap) is the highest point, the nose (front bulge) the
  // point farthest towards -y, the left hip at +x; the mesh keeps its
  // orientation and its volume scales by 1000^3.
  int top = 0, front = 0;
  for (int i = 0; i < a.V; ++i) {
    if (m.template_vertices[static_cast<size_t>(i)].z() > m.template_vertices[static_cast<size_t>(top)].z()) top = i;
    if (m.template_vertices[static_cast<size_t>(i)].y() < m.template_vertices[static_cast<size_t>(front)].y()) front = i;
  }
  EXPECT_EQ(top, a.V - 1);
  EXPECT_EQ(front, 7 * 8 + 2);
  const PosedBody rest = pose_body(m, zero_params(m));
  EXPECT_GT(rest.joints[static_cast<size_t>(m.joint_index("left_hip"))].x(), 50.0);
  EXPECT_LT(rest.joints[static_cast<size_t>(m.joint_index("right_hip"))].x(), -50.0);
  std::vector<Vec3> smpl_v;
  std::vector<std::array<int, 3>> smpl_f;
  for (int i = 0; i < a.V; ++i) smpl_v.push_back(at3(a.v_template, i));
  for (int t = 0; t < a.F; ++t)
    smpl_f.push_back({static_cast<int>(a.f[static_cast<size_t>(3 * t)]), static_cast<int>(a.f[static_cast<size_t>(3 * t + 1)]),
                      static_cast<int>(a.f[static_cast<size_t>(3 * t + 2)])});
  EXPECT_GT(signed_volume(smpl_v, smpl_f), 0.0);
  EXPECT_NEAR(signed_volume(m.template_vertices, m.faces), 1e9 * signed_volume(smpl_v, smpl_f), 1e-3);
  // Sparse regressor and weights keep exactly the file's non-zeros.
  EXPECT_EQ(m.joint_regressor.nonZeros(),
            std::count_if(a.J_regressor.begin(), a.J_regressor.end(), [](double x) { return x != 0.0; }));
  EXPECT_EQ(m.skinning_weights.nonZeros(),
            std::count_if(a.weights.begin(), a.weights.end(), [](double x) { return x != 0.0; }));
}

TEST(SmplModelNpz, PosingMatchesSmplForwardPassInSmplFrame) {
  TempDir dir;
  const SmplArrays a = smpl_test_arrays();
  const BodyModel m = load_smpl_model(dir.write("m.npz", smpl_test_npz(a)));
  ASSERT_TRUE(m.has_pose_basis());
  const Mat3 C = smpl_to_knitforge_axes();
  EXPECT_NEAR(C.determinant(), 1.0, 1e-15);
  Eigen::VectorXd beta(3);
  beta << 0.8, -1.3, 2.0;
  std::vector<Vec3> theta_smpl;
  for (int j = 0; j < 24; ++j) theta_smpl.emplace_back(0.3 * std::sin(j + 0.5), 0.4 * std::cos(2.0 * j), 0.25 * std::sin(3.0 * j + 1.0));
  const Vec3 trans_m(0.1, -0.2, 0.35);
  const std::vector<Vec3> expected = smpl_forward(a, beta, theta_smpl, trans_m);

  BodyParams p = zero_params(m);
  p.shape = beta;
  for (int j = 0; j < 24; ++j) p.joint_rotations[static_cast<size_t>(j)] = C * theta_smpl[static_cast<size_t>(j)];
  p.translation_mm = 1000.0 * (C * trans_m);
  const PosedBody posed = pose_body(m, p);
  double worst = 0.0, moved = 0.0;
  for (int i = 0; i < a.V; ++i) {
    const Vec3 want = 1000.0 * (C * expected[static_cast<size_t>(i)]);
    worst = std::max(worst, (posed.vertices[static_cast<size_t>(i)] - want).norm());
    moved = std::max(moved, (posed.vertices[static_cast<size_t>(i)] - m.template_vertices[static_cast<size_t>(i)]).norm());
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(moved, 100.0);  // the pose is far from the rest: the comparison means something
  // Without the pose-corrective mapping (identity instead of C^T (x) C^T)
  // the result would differ: the correctives here move vertices by mm.
  BodyModel no_correctives = m;
  no_correctives.pose_basis.resize(0, 0);
  const PosedBody plain = pose_body(no_correctives, p);
  double diff = 0.0;
  for (int i = 0; i < a.V; ++i) diff = std::max(diff, (plain.vertices[static_cast<size_t>(i)] - posed.vertices[static_cast<size_t>(i)]).norm());
  EXPECT_GT(diff, 1.0);
}

TEST(SmplModelNpz, NamedPosesApplyInKnitforgeAxes) {
  // body_pose.h: rotating the left shoulder about +y lowers the left (+x)
  // side; in the converted model the +x side of the shoulder ring goes down.
  TempDir dir;
  const BodyModel m = load_smpl_model(dir.write("m.npz", smpl_test_npz(smpl_test_arrays())));
  const PosedBody t = pose_body(m, pose_preset(m, "t-pose"));
  const PosedBody apose = pose_body(m, pose_preset(m, "a-pose"));
  const auto left = static_cast<size_t>(7 * 8 + 0), right = static_cast<size_t>(7 * 8 + 4);
  EXPECT_GT(t.vertices[left].x(), 100.0);
  EXPECT_LT(apose.vertices[left].z(), t.vertices[left].z() - 5.0);
  EXPECT_LT(apose.vertices[right].z(), t.vertices[right].z() - 5.0);
}

TEST(SmplModelNpz, OtherJointCountsGetNumberedNamesAndShapesCanBeLimited) {
  // A 3-joint model (SMPL+H and SMPL-X have other counts than 24).
  SmplArrays a = smpl_test_arrays();
  const int J = 3;
  std::vector<double> jr(a.J_regressor.begin(), a.J_regressor.begin() + J * a.V);
  std::vector<double> w(static_cast<size_t>(a.V * J), 0.0);
  for (int i = 0; i < a.V; ++i) w[static_cast<size_t>(i * J + (i % J))] = 1.0;
  a.J = J;
  a.J_regressor = jr;
  a.weights = w;
  a.kintree = {-1, 0, 0, 0, 1, 2};
  a.posedirs.assign(static_cast<size_t>(a.V * 3 * a.P()), 0.001);
  TempDir dir;
  SmplLoadOptions o;
  o.max_shapes = 2;
  const BodyModel m = load_smpl_model(dir.write("smplx_like.npz", smpl_test_npz(a)), o);
  EXPECT_EQ(m.joint_names, (std::vector<std::string>{"joint_0", "joint_1", "joint_2"}));
  EXPECT_EQ(m.num_shapes(), 2);
  EXPECT_EQ(m.pose_basis.cols(), 18);
  EXPECT_CONTAINS(invalid_input([&] { pose_preset(m, "a-pose"); }), "has no joint 'left_shoulder'");
  // No posedirs at all: a model without pose correctives.
  const BodyModel plain = load_smpl_model(dir.write("plain.npz", smpl_test_npz(a, {{"posedirs", ""}})));
  EXPECT_FALSE(plain.has_pose_basis());
}

TEST(SmplModelNpz, Float32WeightsAreRenormalised) {
  SmplArrays a = smpl_test_arrays();
  for (double& x : a.weights) x = x == 0.0 ? 0.0 : x * (1.0 + 3e-7);
  TempDir dir;
  const BodyModel m = load_smpl_model(dir.write(
      "f4.npz", smpl_test_npz(a, {{"weights", npy_bytes("<f4", {a.V, a.J}, raw_bytes<float>(a.weights))}})));
  for (int i = 0; i < m.num_vertices(); ++i) EXPECT_NEAR(m.skinning_weights.row(i).sum(), 1.0, 1e-12);
}

TEST(SmplModelNpz, RefusesMalformedFilesNamingTheEntry) {
  TempDir dir;
  const SmplArrays good = smpl_test_arrays();
  auto expect = [](const std::string& msg, const std::string& entry, const std::string& what) {
    EXPECT_CONTAINS(msg, "bad.npz: entry '" + entry + ".npy'");
    EXPECT_CONTAINS(msg, what);
  };
  expect(refused(dir, good, {{"weights", ""}}), "weights", "is missing");
  expect(refused(dir, good, {{"v_template", npy_bytes(">f8", {good.V, 3}, std::string(static_cast<size_t>(good.V) * 24, '\0'))}}),
         "v_template", "big-endian");
  expect(refused(dir, good, {{"J_regressor", npy_bytes("|O", {}, "\x80\x02N.")}}), "J_regressor", "Python objects");
  std::string header = npy_f8({good.V, 3, good.K}, good.shapedirs);
  header.replace(header.find("'descr'"), 7, "'descx'");
  expect(refused(dir, good, {{"shapedirs", header}}), "shapedirs", "bad .npy header");
  expect(refused(dir, good, {{"weights", npy_f8({good.V, good.J - 1}, std::vector<double>(static_cast<size_t>(good.V * (good.J - 1)), 0.0))}}),
         "weights", "dimension 1 is 23, expected 24");
  expect(refused(dir, good, {{"shapedirs", npy_f8({good.V, 3}, std::vector<double>(static_cast<size_t>(good.V * 3), 0.0))}}),
         "shapedirs", "expected 3 dimensions");
  expect(refused(dir, good, {{"posedirs", npy_f8({good.V, 3, 9}, std::vector<double>(static_cast<size_t>(good.V * 27), 0.0))}}),
         "posedirs", "9 (J - 1)");
  expect(refused(dir, good, {{"f", npy_f8({good.F, 3}, std::vector<double>(static_cast<size_t>(good.F * 3), 0.0))}}), "f",
         "must be integers");
  SmplArrays a = good;
  a.f[5] = a.V;
  expect(refused(dir, a), "f", "face 1 uses vertex");
  a = good;
  a.w(3, 0) += 0.1;
  expect(refused(dir, a), "weights", "the weights of vertex 3 sum to 1.1");
  a = good;
  a.w(3, 0) -= 1.5;
  a.w(3, 1) += 1.5;
  expect(refused(dir, a), "weights", "vertex 3 has weight");
  a = good;
  a.kintree[5] = 7;  // joint 5's parent after it
  expect(refused(dir, a), "kintree_table", "joint 5 has parent 7; parents must precede");
  a = good;
  a.kintree[0] = 0;
  expect(refused(dir, a), "kintree_table", "root's parent must be a sentinel");
  a = good;
  a.kintree[24 + 3] = 4;
  expect(refused(dir, a), "kintree_table", "row 1 (joint ids)");
  a = good;
  a.J_regressor[0] += 0.5;
  expect(refused(dir, a), "J_regressor", "row 0 ('pelvis') sums to");
  a = good;
  a.v_template[4] = std::nan("");
  expect(refused(dir, a), "v_template", "element 4 is not finite");
  // A truncated archive names the file.
  const std::string whole = smpl_test_npz(good);
  const std::string p = dir.write("cut.npz", whole.substr(0, whole.size() - 100));
  EXPECT_CONTAINS(io_error([&] { load_smpl_model(p); }), "cut.npz");
}
