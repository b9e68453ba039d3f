#include "knitforge/body/smpl_model_npz.h"

#include <cmath>
#include <filesystem>

#include <fmt/core.h>

#include "knitforge/body/smpl_body_parts.h"
#include "knitforge/io/read_npz.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr double kMetresToMm = 1000.0;
constexpr size_t kSmplBodyJoints = 22;  // pelvis .. right_wrist

// Reads one array and checks its number of dimensions, with the entry named
// in every message.
class SmplFile {
 public:
  explicit SmplFile(const std::string& path) : npz_(path) {}

  bool has(const std::string& key) const { return npz_.contains(key); }

  NpyArray array(const std::string& key, size_t dims, const std::string& layout) const {
    if (!npz_.contains(key))
      fail(key, fmt::format("is missing; an SMPL model file has v_template, f, shapedirs, posedirs, J_regressor, "
                            "kintree_table and weights"));
    NpyArray a = npz_.read(key);
    if (a.shape.size() != dims)
      fail(key, fmt::format("has shape {}, expected {} dimensions ({})", a.shape_text(), dims, layout));
    if (!a.is_integer) {
      for (size_t i = 0; i < a.doubles.size(); ++i)
        if (!std::isfinite(a.doubles[i])) fail(key, fmt::format("element {} is not finite", i));
    }
    return a;
  }

  void expect_dim(const NpyArray& a, const std::string& key, size_t d, int64_t n, const std::string& why) const {
    if (a.shape[d] != n)
      fail(key, fmt::format("has shape {}: dimension {} is {}, expected {} ({})", a.shape_text(), d, a.shape[d], n,
                            why));
  }

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw IOError(fmt::format("{}: entry '{}.npy': {}", npz_.path(), key, what));
  }

 private:
  NpzReader npz_;
};

// Row sums of a dense rows x cols array (C order).
std::vector<double> row_sums(const NpyArray& a, int64_t rows, int64_t cols) {
  std::vector<double> sums(static_cast<size_t>(rows), 0.0);
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; ++c) sums[static_cast<size_t>(r)] += a.value(r * cols + c);
  return sums;
}

// The non-zeros of a dense rows x cols array, row r divided by divisor[r]
// (none when `divisor` is empty).
RowSparse sparse_rows(const NpyArray& a, int64_t rows, int64_t cols, const std::vector<double>& divisor) {
  std::vector<Eigen::Triplet<double>> trip;
  for (int64_t r = 0; r < rows; ++r) {
    for (int64_t c = 0; c < cols; ++c) {
      const double x = a.value(r * cols + c);
      if (x != 0.0)
        trip.emplace_back(static_cast<int>(r), static_cast<int>(c),
                          divisor.empty() ? x : x / divisor[static_cast<size_t>(r)]);
    }
  }
  RowSparse m(static_cast<int>(rows), static_cast<int>(cols));
  m.setFromTriplets(trip.begin(), trip.end());
  return m;
}

}  // namespace

const std::vector<std::string>& smpl_joint_names() {
  static const std::vector<std::string> names = {
      "pelvis",      "left_hip",      "right_hip",      "spine1",     "left_knee",   "right_knee",
      "spine2",      "left_ankle",    "right_ankle",    "spine3",     "left_foot",   "right_foot",
      "neck",        "left_collar",   "right_collar",   "head",       "left_shoulder", "right_shoulder",
      "left_elbow",  "right_elbow",   "left_wrist",     "right_wrist", "left_hand",  "right_hand"};
  return names;
}

Mat3 smpl_to_knitforge_axes() {
  Mat3 c;
  c << 1, 0, 0,  //
      0, 0, -1,  //
      0, 1, 0;
  return c;
}

BodyModel load_smpl_model(const std::string& path, const SmplLoadOptions& options) {
  if (options.max_shapes < 0) throw InvalidInput(fmt::format("load_smpl_model: max_shapes is {}, must be >= 0", options.max_shapes));
  if (!(options.weight_sum_tolerance >= 0.0 && options.weight_sum_tolerance < 0.5))
    throw InvalidInput("load_smpl_model: weight_sum_tolerance must be in [0, 0.5)");
  const SmplFile file(path);
  const Mat3 C = smpl_to_knitforge_axes();
  BodyModel m;
  m.name = std::filesystem::path(path).filename().string();

  const NpyArray vt = file.array("v_template", 2, "V x 3 rest vertices");
  file.expect_dim(vt, "v_template", 1, 3, "x, y, z");
  const int64_t V = vt.shape[0];
  if (V < 4) file.fail("v_template", fmt::format("has {} vertices; a body needs at least 4", V));
  if (V > (int64_t{1} << 28)) file.fail("v_template", fmt::format("has {} vertices, too many", V));
  m.template_vertices.resize(static_cast<size_t>(V));
  for (int64_t i = 0; i < V; ++i)
    m.template_vertices[static_cast<size_t>(i)] =
        kMetresToMm * (C * Vec3(vt.value(3 * i), vt.value(3 * i + 1), vt.value(3 * i + 2)));

  const NpyArray f = file.array("f", 2, "F x 3 triangles");
  file.expect_dim(f, "f", 1, 3, "triangles");
  if (!f.is_integer) file.fail("f", fmt::format("has dtype '{}'; vertex indices must be integers", f.dtype));
  if (f.shape[0] < 1) file.fail("f", "has no faces");
  m.faces.resize(static_cast<size_t>(f.shape[0]));
  for (int64_t t = 0; t < f.shape[0]; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int64_t v = f.ints[static_cast<size_t>(3 * t + k)];
      if (v < 0 || v >= V) file.fail("f", fmt::format("face {} uses vertex {}, outside [0, {})", t, v, V));
      m.faces[static_cast<size_t>(t)][static_cast<size_t>(k)] = static_cast<int>(v);
    }
  }

  const NpyArray kt = file.array("kintree_table", 2, "2 x J: parents, joint ids");
  file.expect_dim(kt, "kintree_table", 0, 2, "row 0 parents, row 1 joint ids");
  if (!kt.is_integer) file.fail("kintree_table", fmt::format("has dtype '{}'; joint indices must be integers", kt.dtype));
  const int64_t J = kt.shape[1];
  if (J < 1 || J > 10000) file.fail("kintree_table", fmt::format("has {} joints", J));
  m.parents.resize(static_cast<size_t>(J));
  for (int64_t j = 0; j < J; ++j) {
    const int64_t p = kt.ints[static_cast<size_t>(j)], id = kt.ints[static_cast<size_t>(J + j)];
    if (id != j)
      file.fail("kintree_table", fmt::format("row 1 (joint ids) has {} at column {}; joints must be listed in order 0..{}",
                                             id, j, J - 1));
    if (j == 0) {
      if (p >= 0 && p < J)
        file.fail("kintree_table", fmt::format("joint 0 has parent {}; the root's parent must be a sentinel outside "
                                               "[0, {}) such as 4294967295 or -1", p, J));
      m.parents[0] = -1;
    } else {
      if (p < 0 || p >= j)
        file.fail("kintree_table", fmt::format("joint {} has parent {}; parents must precede their children (in "
                                               "[0, {}))", j, p, j));
      m.parents[static_cast<size_t>(j)] = static_cast<int>(p);
    }
  }
  if (J == static_cast<int64_t>(smpl_joint_names().size())) {
    m.joint_names = smpl_joint_names();
  } else {
    for (int64_t j = 0; j < J; ++j) m.joint_names.push_back(fmt::format("joint_{}", j));
    // SMPL+H (52) and SMPL-X (55) begin with SMPL's 22 body joints.
    if (J == 52 || J == 55)
      for (size_t j = 0; j < kSmplBodyJoints; ++j) m.joint_names[j] = smpl_joint_names()[j];
  }

  const NpyArray sd = file.array("shapedirs", 3, "V x 3 x K shape directions");
  file.expect_dim(sd, "shapedirs", 0, V, "the vertices of v_template");
  file.expect_dim(sd, "shapedirs", 1, 3, "x, y, z");
  const int64_t K_all = sd.shape[2];
  const int64_t K = options.max_shapes > 0 ? std::min<int64_t>(K_all, options.max_shapes) : K_all;
  m.shape_basis.resize(3 * V, K);
  for (int64_t i = 0; i < V; ++i) {
    for (int64_t k = 0; k < K; ++k) {
      const Vec3 d(sd.value((3 * i) * K_all + k), sd.value((3 * i + 1) * K_all + k), sd.value((3 * i + 2) * K_all + k));
      m.shape_basis.block<3, 1>(3 * i, k) = kMetresToMm * (C * d);
    }
  }
  for (int64_t k = 0; k < K; ++k) m.shape_names.push_back(fmt::format("beta{}", k));

  if (file.has("posedirs")) {
    const NpyArray pd = file.array("posedirs", 3, "V x 3 x 9(J-1) pose-corrective directions");
    file.expect_dim(pd, "posedirs", 0, V, "the vertices of v_template");
    file.expect_dim(pd, "posedirs", 1, 3, "x, y, z");
    file.expect_dim(pd, "posedirs", 2, 9 * (J - 1), "9 (J - 1) for the J joints of kintree_table");
    const int64_t P = 9 * (J - 1);
    if (P > 0) {
      Eigen::MatrixXd rotated(3 * V, P);
      for (int64_t i = 0; i < V; ++i)
        for (int64_t p = 0; p < P; ++p)
          rotated.block<3, 1>(3 * i, p) =
              kMetresToMm * (C * Vec3(pd.value((3 * i) * P + p), pd.value((3 * i + 1) * P + p), pd.value((3 * i + 2) * P + p)));
      // SMPL's feature is vec(R - I) in its frame = (C^T (x) C^T) vec(R' - I)
      // with R' = C R C^T ours; row-major vec, so (A (x) B)(3r+c, 3a+b) = A(r,a) B(c,b).
      Eigen::Matrix<double, 9, 9> kron;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) kron(3 * r + c, 3 * a + b) = C(a, r) * C(b, c);
      m.pose_basis.resize(3 * V, P);
      for (int64_t j = 0; j < J - 1; ++j) m.pose_basis.middleCols<9>(9 * j) = rotated.middleCols<9>(9 * j) * kron;
    }
  }

  const NpyArray jr = file.array("J_regressor", 2, "J x V, dense");
  file.expect_dim(jr, "J_regressor", 0, J, "the joints of kintree_table");
  file.expect_dim(jr, "J_regressor", 1, V, "the vertices of v_template");
  const std::vector<double> jr_sums = row_sums(jr, J, V);
  for (int64_t j = 0; j < J; ++j) {
    if (std::abs(jr_sums[static_cast<size_t>(j)] - 1.0) > 1e-3)
      file.fail("J_regressor", fmt::format("row {} ('{}') sums to {}, not 1", j, m.joint_names[static_cast<size_t>(j)],
                                           jr_sums[static_cast<size_t>(j)]));
  }
  m.joint_regressor = sparse_rows(jr, J, V, {});

  const NpyArray w = file.array("weights", 2, "V x J skinning weights");
  file.expect_dim(w, "weights", 0, V, "the vertices of v_template");
  file.expect_dim(w, "weights", 1, J, "the joints of kintree_table");
  for (int64_t k = 0; k < V * J; ++k) {
    if (w.value(k) < 0.0)
      file.fail("weights", fmt::format("vertex {} has weight {} for joint {} (must be >= 0)", k / J, w.value(k), k % J));
  }
  const std::vector<double> w_sums = row_sums(w, V, J);
  for (int64_t i = 0; i < V; ++i) {
    if (!(std::abs(w_sums[static_cast<size_t>(i)] - 1.0) <= options.weight_sum_tolerance))
      file.fail("weights", fmt::format("the weights of vertex {} sum to {}, not 1", i, w_sums[static_cast<size_t>(i)]));
  }
  m.skinning_weights = sparse_rows(w, V, J, w_sums);  // rows rescaled to sum to 1 exactly

  validate_body_model(m);
  if (options.derive_labels) {
    // Part labels, fields and landmarks from the model's own data; a model
    // they cannot be derived for loads without them and says why.
    try {
      label_smpl_body(m);
    } catch (const InvalidInput& e) {
      m.vertex_parts.clear();
      m.part_fields.clear();
      m.landmarks.clear();
      m.labels_note = e.what();
    }
  } else {
    m.labels_note = fmt::format("body model '{}' was loaded without part labels (SmplLoadOptions::derive_labels)", m.name);
  }
  if (!m.vertex_parts.empty()) validate_body_model(m);
  return m;
}

}  // namespace knitforge
