#include "knitforge/evaluate/rigid_align.h"

#include <cmath>
#include <limits>

#include <fmt/core.h>
#include <Eigen/SVD>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

void check_weights(std::span<const double> weights, size_t n, const char* what) {
  if (weights.empty()) return;
  if (weights.size() != n) {
    throw InvalidInput(
        fmt::format("{}: {} weights for {} points (give one per point, or none)", what, weights.size(), n));
  }
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(weights[i]) && weights[i] >= 0)) {
      throw InvalidInput(fmt::format("{}: weight {} is {} (must be finite and >= 0)", what, i, weights[i]));
    }
    total += weights[i];
  }
  if (!(total > 0)) throw InvalidInput(fmt::format("{}: all weights are zero", what));
}

void check_points(std::span<const Vec3> pts, const char* what, const char* name) {
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!pts[i].allFinite()) throw InvalidInput(fmt::format("{}: {} point {} is not finite", what, name, i));
  }
}

}  // namespace

RigidTransform rigid_align(std::span<const Vec3> from, std::span<const Vec3> to,
                           std::span<const double> weights) {
  constexpr const char* kWhat = "rigid_align";
  if (from.empty()) throw InvalidInput("rigid_align: no points");
  if (from.size() != to.size()) {
    throw InvalidInput(
        fmt::format("rigid_align: {} source points but {} target points", from.size(), to.size()));
  }
  check_points(from, kWhat, "source");
  check_points(to, kWhat, "target");
  check_weights(weights, from.size(), kWhat);
  const size_t n = from.size();
  auto w = [&](size_t i) { return weights.empty() ? 1.0 : weights[i]; };
  double total = 0;
  Vec3 cf = Vec3::Zero(), ct = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) {
    total += w(i);
    cf += w(i) * from[i];
    ct += w(i) * to[i];
  }
  cf /= total;
  ct /= total;
  Mat3 S = Mat3::Zero();
  for (size_t i = 0; i < n; ++i) S += w(i) * (from[i] - cf) * (to[i] - ct).transpose();
  const Eigen::JacobiSVD<Mat3> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat3& U = svd.matrixU();
  const Mat3& V = svd.matrixV();
  Mat3 D = Mat3::Identity();
  if ((V * U.transpose()).determinant() < 0) D(2, 2) = -1;  // the smallest singular value flips
  RigidTransform out;
  out.rotation = V * D * U.transpose();
  out.translation = ct - out.rotation * cf;
  return out;
}

IcpResult align_to_surface(std::span<const Vec3> points, const TriMesh& target, const RigidTransform& initial,
                           const IcpOptions& options, std::span<const double> weights) {
  if (points.empty()) throw InvalidInput("align_to_surface: no points");
  return align_to_surface(points, SurfaceBvh(target), initial, options, weights);
}

IcpResult align_to_surface(std::span<const Vec3> points, const SurfaceBvh& target,
                           const RigidTransform& initial, const IcpOptions& options,
                           std::span<const double> weights) {
  constexpr const char* kWhat = "align_to_surface";
  if (points.empty()) throw InvalidInput("align_to_surface: no points");
  if (options.max_iterations < 0 || !(options.tolerance >= 0)) {
    throw InvalidInput(fmt::format("align_to_surface: max_iterations {} must be >= 0 and tolerance {} >= 0",
                                   options.max_iterations, options.tolerance));
  }
  if (!initial.rotation.allFinite() || !initial.translation.allFinite()) {
    throw InvalidInput("align_to_surface: the initial transform is not finite");
  }
  check_points(points, kWhat, "input");
  check_weights(weights, points.size(), kWhat);
  const size_t n = points.size();
  double total = 0;
  for (size_t i = 0; i < n; ++i) total += weights.empty() ? 1.0 : weights[i];

  auto w = [&](size_t i) { return weights.empty() ? 1.0 : weights[i]; };
  // Closest points and normals for transform T into (c, nrm); returns the
  // weighted RMS distance.
  // The face each point last matched: the next round's search starts from
  // it (the same closest points, found faster; SurfaceBvh::closest_point()).
  std::vector<int> last_face(n, -1);
  auto match = [&](const RigidTransform& T, std::vector<Vec3>& c, std::vector<Vec3>& nrm) {
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
      const Vec3 x = T.apply(points[i]);
      const ClosestPoint sp = target.closest_point(x, last_face[i]);
      last_face[i] = sp.face;
      c[i] = sp.point;
      // The gradient of the distance (exact also on edges and vertices);
      // the face normal for points on the surface.
      nrm[i] = sp.distance > 0 ? Vec3((x - sp.point) / sp.distance) : sp.normal;
      sum += w(i) * sp.distance * sp.distance;
    }
    return std::sqrt(sum / total);
  };
  // One linearised point-to-plane step (Gauss-Newton on sum w ((x - c).n)^2,
  // rotating about the weighted centroid), slightly damped so directions the
  // surface does not constrain (sliding along a plane) stay put.
  auto plane_step = [&](const RigidTransform& T, const std::vector<Vec3>& c, const std::vector<Vec3>& nrm) {
    Vec3 centre = Vec3::Zero();
    for (size_t i = 0; i < n; ++i) centre += w(i) * T.apply(points[i]);
    centre /= total;
    Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> Atb = Eigen::Matrix<double, 6, 1>::Zero();
    for (size_t i = 0; i < n; ++i) {
      if (nrm[i].isZero()) continue;
      const Vec3 x = T.apply(points[i]);
      Eigen::Matrix<double, 6, 1> a;
      a << (x - centre).cross(nrm[i]), nrm[i];
      AtA += w(i) * a * a.transpose();
      Atb += w(i) * a * (c[i] - x).dot(nrm[i]);
    }
    const double damping = 1e-9 * AtA.trace() + 1e-300;
    AtA.diagonal().array() += damping;
    const Eigen::Matrix<double, 6, 1> xi = AtA.ldlt().solve(Atb);
    const Vec3 omega = xi.head<3>();
    const double angle = omega.norm();
    const Mat3 dR = angle > 0 ? Mat3(Eigen::AngleAxisd(angle, omega / angle)) : Mat3::Identity();
    // x -> dR (x - centre) + centre + tau, after T.
    const RigidTransform step{dR, centre + xi.tail<3>() - dR * centre};
    return step.after(T);
  };

  std::vector<Vec3> closest(n), normals(n), closest2(n), normals2(n);
  IcpResult out;
  out.transform = initial;
  out.rms = out.initial_rms = match(initial, closest, normals);
  for (int it = 0; it < options.max_iterations; ++it) {
    if (out.rms == 0) {
      out.converged = true;
      break;
    }
    out.iterations = it + 1;
    // Point-to-plane converges fast; when its step does not lower the true
    // RMS, the point-to-point (Kabsch) step does, or nothing does.
    RigidTransform next = plane_step(out.transform, closest, normals);
    double rms = next.rotation.allFinite() && next.translation.allFinite()
                     ? match(next, closest2, normals2)
                     : std::numeric_limits<double>::infinity();
    if (!(rms < out.rms)) {
      next = rigid_align(points, closest, weights);
      rms = match(next, closest2, normals2);
    }
    if (!(rms < out.rms)) {  // no progress (rounding): keep the current transform
      out.converged = true;
      break;
    }
    const double gain = (out.rms - rms) / out.rms;
    out.transform = next;
    out.rms = rms;
    closest.swap(closest2);
    normals.swap(normals2);
    if (gain < options.tolerance) {
      out.converged = true;
      break;
    }
  }
  return out;
}

}  // namespace knitforge
