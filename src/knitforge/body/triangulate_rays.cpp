#include "knitforge/body/triangulate_rays.h"

#include <cmath>

#include <Eigen/Dense>
#include <fmt/core.h>

#include "knitforge/body/axis_angle.h"
#include "knitforge/util/errors.h"

namespace knitforge {

Ray camera_ray(const PinholeCamera& camera, const Vec2& pixel) {
  if (!camera.K.allFinite() || !camera.R.allFinite() || !camera.t.allFinite() || !pixel.allFinite())
    throw InvalidInput("camera ray: the camera or the pixel is not finite");
  const Eigen::FullPivLU<Mat3> lu(camera.K);
  if (!lu.isInvertible()) throw InvalidInput("camera ray: the intrinsic matrix K is singular");
  Ray r;
  r.origin = -camera.R.transpose() * camera.t;
  r.direction = (camera.R.transpose() * lu.solve(Vec3(pixel.x(), pixel.y(), 1.0))).normalized();
  return r;
}

Vec2 project_to_pixel(const PinholeCamera& camera, const Vec3& point) {
  const Vec3 c = camera.R * point + camera.t;
  if (!(c.z() > 0.0)) throw InvalidInput("project to pixel: the point is not in front of the camera");
  const Vec3 h = camera.K * c;
  return {h.x() / h.z(), h.y() / h.z()};
}

RayPoint triangulate_rays(std::span<const Ray> rays) {
  if (rays.size() < 2)
    throw InvalidInput(fmt::format("triangulate rays: a keypoint needs at least 2 views, it has {}", rays.size()));
  const auto n = static_cast<Eigen::Index>(rays.size());
  Eigen::MatrixXd M(3 * n, 3);
  Eigen::VectorXd b(3 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Ray& r = rays[static_cast<size_t>(i)];
    const double len = r.direction.norm();
    if (!(len > 0.0) || !std::isfinite(len) || !r.origin.allFinite())
      throw InvalidInput(fmt::format("triangulate rays: ray {} has a zero or non-finite direction or origin", i));
    const Vec3 d = r.direction / len;
    M.middleRows<3>(3 * i) = skew(d);          // eq. 5.15
    b.segment<3>(3 * i) = d.cross(r.origin);   // eq. 5.16 (sign: see the header)
  }
  const Mat3 A = M.transpose() * M;
  const Vec3 g = M.transpose() * b;
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(A);
  RayPoint out;
  out.conditioning = eig.eigenvalues()(0) / std::max(eig.eigenvalues()(2), 1e-300);
  if (!(out.conditioning >= 1e-8))
    throw InvalidInput(fmt::format("triangulate rays: the {} rays are (nearly) parallel, the point is not "
                                   "determined (conditioning {:.1e}); use views from other directions",
                                   rays.size(), out.conditioning));
  out.point = A.ldlt().solve(g);
  const Eigen::VectorXd res = M * out.point - b;
  out.rms_distance_mm = std::sqrt(res.squaredNorm() / static_cast<double>(n));
  return out;
}

}  // namespace knitforge
