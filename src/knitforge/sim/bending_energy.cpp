#include "knitforge/sim/bending_energy.h"

#include <cmath>

#include <unsupported/Eigen/AutoDiff>

namespace knitforge {

namespace {

// The hinge's edge e = x1 - x0 and its two (unnormalised) triangle normals,
// formed once for the angle, its gradient and the degeneracy test, for
// scalars S: double, or forward-mode dual numbers whose derivatives give
// the exact ∇²θ.
template <class S>
struct HingeGeometry {
  using V = Eigen::Matrix<S, 3, 1>;
  V e, d2, d3, na, nb;
  S e2, en;
  HingeGeometry(const V& x0, const V& x1, const V& x2, const V& x3)
      : e(x1 - x0), d2(x2 - x0), d3(x3 - x0), na(e.cross(d2)), nb(d3.cross(e)), e2(e.squaredNorm()), en(sqrt(e2)) {}

  /// θ, 0 for a zero-length edge.
  S angle() const { return en > 0 ? S(atan2(na.cross(nb).dot(e) / en, na.dot(nb))) : S(0); }
  /// Heights h = |n| / |e|: degenerate triangles have no defined angle
  /// gradient.
  bool degenerate() const { return !(e2 > 0) || sqrt(na.squaredNorm()) <= 1e-9 * e2 || sqrt(nb.squaredNorm()) <= 1e-9 * e2; }
  /// ∇θ (12-vector, exact; Bridson et al. 2003).
  Eigen::Matrix<S, 12, 1> angle_gradient() const {
    const V g2 = -na * (en / na.squaredNorm());  // -n̂_A / h_A
    const V g3 = -nb * (en / nb.squaredNorm());
    const S ta = d2.dot(e) / e2, tb = d3.dot(e) / e2;
    Eigen::Matrix<S, 12, 1> grad;
    grad.template segment<3>(0) = -(S(1) - ta) * g2 - (S(1) - tb) * g3;
    grad.template segment<3>(3) = -ta * g2 - tb * g3;
    grad.template segment<3>(6) = g2;
    grad.template segment<3>(9) = g3;
    return grad;
  }
};

using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 12, 1>>;

}  // namespace

double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  return HingeGeometry<double>(x0, x1, x2, x3).angle();
}

ElementEnergy<4> hinge_element_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                                      const BendingHinge& hinge, Derivatives what, PsdProjection projection) {
  ElementEnergy<4> out;
  const HingeGeometry<double> h(x0, x1, x2, x3);
  const double theta = h.angle();
  const double k = hinge.stiffness;
  out.value = k * theta * theta;
  if (what == Derivatives::Value || h.degenerate()) return out;
  if (what == Derivatives::Gradient || projection == PsdProjection::Clamp) {
    const Eigen::Matrix<double, 12, 1> grad = h.angle_gradient();
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
  const Eigen::Matrix<Dual, 12, 1> gd = HingeGeometry<Dual>(d[0], d[1], d[2], d[3]).angle_gradient();
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
  add_element_energies<4>(
      model.hinges.size(),
      [&](std::size_t i, Derivatives what) {
        const BendingHinge& h = model.hinges[i];
        return hinge_element_energy(x.segment<3>(3 * h.v[0]), x.segment<3>(3 * h.v[1]), x.segment<3>(3 * h.v[2]),
                                    x.segment<3>(3 * h.v[3]), h, what, projection);
      },
      [&](std::size_t i) { return model.hinges[i].v; }, out);
}

}  // namespace knitforge
