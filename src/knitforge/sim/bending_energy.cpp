#include "knitforge/sim/bending_energy.h"

#include <cmath>

#include <unsupported/Eigen/AutoDiff>

namespace knitforge {

double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 e = x1 - x0;
  const Vec3 na = e.cross(x2 - x0);
  const Vec3 nb = (x3 - x0).cross(e);
  const double en = e.norm();
  if (!(en > 0)) return 0.0;
  return std::atan2(na.cross(nb).dot(e) / en, na.dot(nb));
}

namespace {

// ∇θ (12-vector, exact; Bridson et al. 2003) for scalars S: double, or
// forward-mode dual numbers whose derivatives give the exact ∇²θ.
template <class S>
Eigen::Matrix<S, 12, 1> angle_gradient(const Eigen::Matrix<S, 3, 1>& x0, const Eigen::Matrix<S, 3, 1>& x1,
                                        const Eigen::Matrix<S, 3, 1>& x2, const Eigen::Matrix<S, 3, 1>& x3) {
  using V = Eigen::Matrix<S, 3, 1>;
  const V e = x1 - x0;
  const S e2 = e.squaredNorm();
  const V na = e.cross(x2 - x0);
  const V nb = (x3 - x0).cross(e);
  const S len = sqrt(e2);
  const V g2 = -na * (len / na.squaredNorm());  // -n̂_A / h_A
  const V g3 = -nb * (len / nb.squaredNorm());
  const S ta = (x2 - x0).dot(e) / e2, tb = (x3 - x0).dot(e) / e2;
  Eigen::Matrix<S, 12, 1> grad;
  grad.template segment<3>(0) = -(S(1) - ta) * g2 - (S(1) - tb) * g3;
  grad.template segment<3>(3) = -ta * g2 - tb * g3;
  grad.template segment<3>(6) = g2;
  grad.template segment<3>(9) = g3;
  return grad;
}

using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 12, 1>>;

}  // namespace

ElementEnergy<4> hinge_element_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                                      const BendingHinge& hinge, Derivatives what, PsdProjection projection) {
  ElementEnergy<4> out;
  if (what == Derivatives::Gradient) {
    // Value and gradient with each cross product formed once: the same
    // expressions as dihedral_angle() and angle_gradient(), so the same bits
    // as the general path below (the L-BFGS phase's line search is made of
    // these evaluations).
    const Vec3 e = x1 - x0, d2 = x2 - x0, d3 = x3 - x0;
    const Vec3 na = e.cross(d2), nb = d3.cross(e);
    const double e2 = e.squaredNorm();
    const double en = std::sqrt(e2);
    const double theta = en > 0 ? std::atan2(na.cross(nb).dot(e) / en, na.dot(nb)) : 0.0;
    const double k = hinge.stiffness;
    out.value = k * theta * theta;
    const double na2 = na.squaredNorm(), nb2 = nb.squaredNorm();
    if (!(e2 > 0) || std::sqrt(na2) <= 1e-9 * e2 || std::sqrt(nb2) <= 1e-9 * e2) return out;
    const Vec3 g2 = -na * (en / na2);
    const Vec3 g3 = -nb * (en / nb2);
    const double ta = d2.dot(e) / e2, tb = d3.dot(e) / e2;
    const double c = 2 * k * theta;
    out.gradient.segment<3>(0) = c * (-(1.0 - ta) * g2 - (1.0 - tb) * g3);
    out.gradient.segment<3>(3) = c * (-ta * g2 - tb * g3);
    out.gradient.segment<3>(6) = c * g2;
    out.gradient.segment<3>(9) = c * g3;
    return out;
  }
  const double theta = dihedral_angle(x0, x1, x2, x3);
  const double k = hinge.stiffness;
  out.value = k * theta * theta;
  if (what == Derivatives::Value) return out;
  const Vec3 e = x1 - x0;
  const double e2 = e.squaredNorm();
  const double la = e.cross(x2 - x0).norm(), lb = (x3 - x0).cross(e).norm();
  // Heights h = |n| / |e|; degenerate triangles have no defined angle gradient.
  if (!(e2 > 0) || la <= 1e-9 * e2 || lb <= 1e-9 * e2) return out;
  if (what == Derivatives::Gradient || projection == PsdProjection::Clamp) {
    const Eigen::Matrix<double, 12, 1> grad = angle_gradient<double>(x0, x1, x2, x3);
    out.gradient = (2 * k * theta) * grad;
    // Clamp: the Gauss-Newton part, positive semi-definite by construction.
    if (what == Derivatives::Hessian) out.hessian = (2 * k) * grad * grad.transpose();
    return out;
  }
  // ∇θ with its Jacobian ∇²θ in one forward-mode pass.
  Eigen::Matrix<Dual, 3, 1> d[4];
  const Vec3* xs[4] = {&x0, &x1, &x2, &x3};
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) d[v][c] = Dual((*xs[v])[c], 12, 3 * v + c);
  const Eigen::Matrix<Dual, 12, 1> gd = angle_gradient<Dual>(d[0], d[1], d[2], d[3]);
  Eigen::Matrix<double, 12, 1> grad;
  Eigen::Matrix<double, 12, 12> hess_theta;
  for (int i = 0; i < 12; ++i) {
    grad[i] = gd[i].value();
    hess_theta.row(i) = gd[i].derivatives().transpose();
  }
  out.gradient = (2 * k * theta) * grad;
  out.hessian = (2 * k) * (grad * grad.transpose() + theta * 0.5 * (hess_theta + hess_theta.transpose()));
  project_psd<12>(out.hessian, projection);
  return out;
}

void add_bending_energy(const SimModel& model, const Eigen::VectorXd& x, EnergyEval& out, PsdProjection projection) {
  const Derivatives what = out.wants_hessian()    ? Derivatives::Hessian
                           : out.wants_gradient() ? Derivatives::Gradient
                                                  : Derivatives::Value;
  for (const BendingHinge& h : model.hinges) {
    const ElementEnergy<4> el = hinge_element_energy(x.segment<3>(3 * h.v[0]), x.segment<3>(3 * h.v[1]),
                                                     x.segment<3>(3 * h.v[2]), x.segment<3>(3 * h.v[3]), h, what, projection);
    out.value += el.value;
    if (what == Derivatives::Value) continue;
    for (int k = 0; k < 4; ++k) out.add_gradient(h.v[k], el.gradient.segment<3>(3 * k));
    if (what == Derivatives::Hessian) out.add_element_hessian<4>(h.v, el.hessian);
  }
}

}  // namespace knitforge
