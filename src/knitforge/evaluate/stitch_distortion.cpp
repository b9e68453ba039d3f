#include "knitforge/evaluate/stitch_distortion.h"

#include <cmath>

#include <Eigen/SVD>
#include <fmt/core.h>

#include "knitforge/convert/relax_stitch_mesh.h"
#include "knitforge/evaluate/rigid_align.h"
#include "knitforge/util/errors.h"

namespace knitforge {

StitchDistortion polygon_distortion(std::span<const Vec3> ideal, std::span<const Vec3> actual) {
  const size_t n = ideal.size();
  if (n != actual.size() || n < 3) {
    throw InvalidInput(fmt::format("polygon distortion: {} ideal and {} actual corners (need the same number, >= 3)",
                                   n, actual.size()));
  }
  for (size_t i = 0; i < n; ++i) {
    if (!ideal[i].allFinite() || !actual[i].allFinite()) {
      throw InvalidInput(fmt::format("polygon distortion: corner {} is not finite", i));
    }
  }
  Vec3 cp = Vec3::Zero(), cq = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) {
    cp += Vec3(ideal[i].x(), ideal[i].y(), 0.0);
    cq += actual[i];
  }
  cp /= static_cast<double>(n);
  cq /= static_cast<double>(n);
  Eigen::Matrix2d PPt = Eigen::Matrix2d::Zero();
  Eigen::Matrix<double, 3, 2> QPt = Eigen::Matrix<double, 3, 2>::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = ideal[i].head<2>() - cp.head<2>();
    PPt += p * p.transpose();
    QPt += (actual[i] - cq) * p.transpose();
  }
  const double scale = PPt.trace();
  if (!(std::abs(PPt.determinant()) > 1e-12 * scale * scale)) {
    throw InvalidInput("polygon distortion: the ideal polygon's corners are collinear");
  }
  const Eigen::Matrix<double, 3, 2> A = QPt * PPt.inverse();
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(A);
  StitchDistortion d;
  d.sigma1 = svd.singularValues()(0);
  d.sigma2 = svd.singularValues()(1);
  d.distortion = std::max(std::abs(d.sigma1 - 1), std::abs(d.sigma2 - 1));

  std::vector<Vec3> flat(n);
  for (size_t i = 0; i < n; ++i) flat[i] = Vec3(ideal[i].x(), ideal[i].y(), 0.0);
  const RigidTransform T = rigid_align(flat, actual);
  double sum = 0;
  for (size_t i = 0; i < n; ++i) sum += (T.apply(flat[i]) - actual[i]).squaredNorm();
  d.rigid_rms = std::sqrt(sum / static_cast<double>(n));
  return d;
}

std::vector<StitchDistortion> stitch_distortion(const StitchMesh& mesh, const KnitParams& params) {
  if (!(std::isfinite(params.stitch_width) && params.stitch_width > 0 && std::isfinite(params.stitch_height) &&
        params.stitch_height > 0)) {
    throw InvalidInput(fmt::format("stitch size {} x {} mm: both must be finite and > 0", params.stitch_width,
                                   params.stitch_height));
  }
  std::vector<Vec3> shapes[kNumStitchTypes];
  for (int t = 0; t < kNumStitchTypes; ++t) shapes[t] = ideal_stitch_shape(static_cast<StitchType>(t), params);
  const int nv = mesh.num_vertices();
  std::vector<StitchDistortion> out(mesh.stitches.size());
  Vec3 q[4];
  for (int s = 0; s < mesh.num_stitches(); ++s) {
    const Stitch& st = mesh.stitches[s];
    const int t = static_cast<int>(st.type);
    if (t >= kNumStitchTypes) throw TopologyError(fmt::format("stitch {} has an unknown type {}", s, t));
    const int n = st.corners();
    for (int k = 0; k < n; ++k) {
      if (st.v[k] < 0 || st.v[k] >= nv) {
        throw TopologyError(fmt::format("stitch {} corner {} is vertex {} (valid: 0..{})", s, k, st.v[k], nv - 1));
      }
      q[k] = mesh.vertices[st.v[k]];
      if (!q[k].allFinite()) throw InvalidInput(fmt::format("stitch mesh vertex {} has a non-finite position", st.v[k]));
    }
    out[s] = polygon_distortion(shapes[t], std::span<const Vec3>(q, n));
  }
  return out;
}

std::vector<double> distortion_values(std::span<const StitchDistortion> d) {
  std::vector<double> out(d.size());
  for (size_t i = 0; i < d.size(); ++i) out[i] = d[i].distortion;
  return out;
}

}  // namespace knitforge
