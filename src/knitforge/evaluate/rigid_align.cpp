#include "knitforge/evaluate/rigid_align.h"

#include <cmath>
#include <limits>

#include <fmt/core.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "knitforge/util/errors.h"
#include "knitforge/util/parallel_ranges.h"

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

// -B⁻¹ g for a symmetric B; when B is not positive definite, B is replaced
// by |B| (its eigenvalues by their absolute values, at least 10⁻⁹ of the
// largest), a descent direction's matrix.
Eigen::Matrix<double, 6, 1> descent_step(Eigen::Matrix<double, 6, 6>& B, const Eigen::Matrix<double, 6, 1>& g) {
  const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(B);
  if (llt.info() == Eigen::Success) return -llt.solve(g);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(B);
  const Eigen::Matrix<double, 6, 1> abs = es.eigenvalues().cwiseAbs();
  const Eigen::Matrix<double, 6, 1> lambda = abs.cwiseMax(1e-9 * abs.maxCoeff() + 1e-300);
  B = es.eigenvectors() * lambda.asDiagonal() * es.eigenvectors().transpose();
  return -es.eigenvectors() * (es.eigenvectors().transpose() * g).cwiseQuotient(lambda);
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
  // The closest points of the points moved by T, into `cp`; returns the
  // weighted RMS distance. Each search starts from the face the entry held
  // before (an earlier round's: the same answer, found faster;
  // SurfaceBvh::closest_point()).
  // The searches run on all hardware threads; the sum is taken in order.
  auto match = [&](const RigidTransform& T, std::vector<ClosestPoint>& cp) {
    parallel_ranges(n, 1024, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) cp[i] = target.closest_point(T.apply(points[i]), cp[i].face);
    });
    double sum = 0;
    for (size_t i = 0; i < n; ++i) sum += w(i) * cp[i].distance * cp[i].distance;
    return std::sqrt(sum / total);
  };
  // The quadratic model of f = 1/2 sum w d^2 for the motion x -> dR (x -
  // centre) + centre + tau after T, dR = exp([omega]x), about (omega, tau) =
  // 0. With r = x - c = d n, q = x - centre and J = dx/d(omega, tau) =
  // [-[q]x, I], the gradient is g = sum w J^T r. The Hessian:
  //  - Newton (`newton` true): sum w J^T H J + sum w (r . d^2x/domega^2), H
  //    the Hessian of 1/2 d^2 at x (n n^T inside a face, I - e e^T on an
  //    edge, I at a corner: exact while the closest points stay on their
  //    features) and the rotation's second-order term sum w (sym(r q^T) -
  //    (r . q) I). That term is large where the distances are (a shape far
  //    from its target, points closest to the target's rim): without it the
  //    steps come out too short and ICP converges slowly (0.87 a round on a
  //    free hemisphere, still moving after 30 rounds).
  //  - Gauss-Newton (point-to-plane): H = n n^T and no second-order term.
  // Slightly damped so directions the surface does not constrain (sliding
  // along a plane) stay put.
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  auto model = [&](const RigidTransform& T, const std::vector<ClosestPoint>& cp, const Vec3& centre, bool newton,
                   Mat6* hessian) {
    Mat6 H = Mat6::Zero();
    Vec6 g = Vec6::Zero();
    for (size_t i = 0; i < n; ++i) {
      const Vec3 x = T.apply(points[i]);
      const Vec3 q = x - centre;
      const Vec3 r = x - cp[i].point;
      g.head<3>() += w(i) * q.cross(r);
      g.tail<3>() += w(i) * r;
      if (!hessian) continue;
      if (newton) {
        Mat3 Q;  // -[q]x = d(omega x q)/d omega
        Q << 0, q.z(), -q.y(), -q.z(), 0, q.x(), q.y(), -q.x(), 0;
        const Mat3 M = cp[i].half_squared_distance_hessian();
        const Mat3 MQ = M * Q;
        const Mat3 rq = r * q.transpose();
        H.topLeftCorner<3, 3>() +=
            w(i) * (Q.transpose() * MQ + 0.5 * (rq + rq.transpose()) - r.dot(q) * Mat3::Identity());
        H.topRightCorner<3, 3>() += w(i) * MQ.transpose();
        H.bottomRightCorner<3, 3>() += w(i) * M;
        continue;
      }
      // The gradient of the distance (exact also on edges and corners); the
      // face normal for points on the surface.
      const Vec3 nrm = cp[i].distance > 0 ? Vec3(r / cp[i].distance) : cp[i].normal;
      if (!nrm.isZero()) {
        Vec6 a;
        a << q.cross(nrm), nrm;
        H += w(i) * a * a.transpose();
      }
    }
    if (hessian) {
      H.bottomLeftCorner<3, 3>() = H.topRightCorner<3, 3>().transpose();
      H.diagonal().array() += 1e-9 * H.trace() + 1e-300;
      *hessian = H;
    }
    return g;
  };
  // The motion xi = (omega, tau) about `centre`, after T.
  auto move = [](const Vec6& xi, const Vec3& centre, const RigidTransform& T) {
    const Vec3 omega = xi.head<3>();
    const double angle = omega.norm();
    const Mat3 dR = angle > 0 ? Mat3(Eigen::AngleAxisd(angle, omega / angle)) : Mat3::Identity();
    return RigidTransform{dR, centre + xi.tail<3>() - dR * centre}.after(T);
  };

  std::vector<ClosestPoint> closest(n), closest2(n);
  IcpResult out;
  out.transform = initial;
  out.rms = out.initial_rms = match(initial, closest);
  // Rotations are about one fixed point (the start's centroid), so the
  // gradients of successive rounds are in the same coordinates.
  Vec3 centre = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) centre += w(i) * initial.apply(points[i]);
  centre /= total;
  // BFGS on the six motion parameters: B starts as (and is reset to) the
  // Newton Hessian and learns from each accepted step (s, y) = (xi, g_new -
  // g): on a mesh the closest points jump between faces, edges and corners,
  // so the curvature along a step differs from any one round's Hessian
  // (smaller where the target is concave).
  Mat6 B;
  bool have_b = false;
  Vec6 g = model(out.transform, closest, centre, false, nullptr);
  int small_gains = 0;
  for (int it = 0; it < options.max_iterations; ++it) {
    if (out.rms == 0) {
      out.converged = true;
      break;
    }
    out.iterations = it + 1;
    // The BFGS step; when it does not lower the true RMS (or B is not
    // positive definite), the Newton step with a fresh Hessian, then the
    // Gauss-Newton (point-to-plane) step, then the point-to-point (Kabsch)
    // step, which never increases it; or nothing.
    double rms = std::numeric_limits<double>::infinity();
    RigidTransform next;
    Vec6 xi = Vec6::Zero();
    for (int kind = have_b ? 0 : 1; kind < 3 && !(rms < out.rms); ++kind) {
      if (kind > 0) {
        model(out.transform, closest, centre, kind == 1, &B);
        have_b = kind == 1;
      }
      xi = descent_step(B, g);
      next = move(xi, centre, out.transform);
      if (next.rotation.allFinite() && next.translation.allFinite()) rms = match(next, closest2);
    }
    const bool secant = rms < out.rms;
    if (!(rms < out.rms)) {
      std::vector<Vec3> c(n);
      for (size_t i = 0; i < n; ++i) c[i] = closest[i].point;
      next = rigid_align(points, c, weights);
      rms = match(next, closest2);
    }
    if (!(rms < out.rms)) {  // no progress (rounding): keep the current transform
      out.converged = true;
      break;
    }
    const double gain = (out.rms - rms) / out.rms;
    out.transform = next;
    out.rms = rms;
    closest.swap(closest2);
    const Vec6 g_next = model(out.transform, closest, centre, false, nullptr);
    const Vec6 y = g_next - g;
    g = g_next;
    if (secant && have_b && xi.dot(y) > 1e-12 * xi.norm() * y.norm()) {
      const Vec6 Bs = B * xi;
      B += y * y.transpose() / y.dot(xi) - Bs * Bs.transpose() / xi.dot(Bs);
    } else if (!secant) {
      have_b = false;
    }
    // Quasi-Newton gains are not monotone (a small one can come before a
    // large one), so two small ones in a row end it.
    small_gains = gain < options.tolerance ? small_gains + 1 : 0;
    if (small_gains == 2) {
      out.converged = true;
      break;
    }
  }
  return out;
}

}  // namespace knitforge
