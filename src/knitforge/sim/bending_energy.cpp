#include "knitforge/sim/bending_energy.h"

#include <cmath>

namespace knitforge {

double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 e = x1 - x0;
  const Vec3 na = e.cross(x2 - x0);
  const Vec3 nb = (x3 - x0).cross(e);
  const double en = e.norm();
  if (!(en > 0)) return 0.0;
  return std::atan2(na.cross(nb).dot(e) / en, na.dot(nb));
}

ElementEnergy<4> hinge_element_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3,
                                      const BendingHinge& hinge, Derivatives what) {
  ElementEnergy<4> out;
  const double theta = dihedral_angle(x0, x1, x2, x3);
  const double k = hinge.stiffness;
  out.value = k * theta * theta;
  if (what == Derivatives::Value) return out;
  const Vec3 e = x1 - x0;
  const double e2 = e.squaredNorm();
  const Vec3 na = e.cross(x2 - x0);
  const Vec3 nb = (x3 - x0).cross(e);
  const double la = na.norm(), lb = nb.norm();
  // Heights h = |n| / |e|; degenerate triangles have no defined angle gradient.
  if (!(e2 > 0) || la <= 1e-9 * e2 || lb <= 1e-9 * e2) return out;
  const double len = std::sqrt(e2);
  const Vec3 g2 = -na * (len / (la * la));  // -n̂_A / h_A
  const Vec3 g3 = -nb * (len / (lb * lb));
  const double ta = (x2 - x0).dot(e) / e2, tb = (x3 - x0).dot(e) / e2;
  Eigen::Matrix<double, 12, 1> grad;
  grad.segment<3>(0) = -(1 - ta) * g2 - (1 - tb) * g3;
  grad.segment<3>(3) = -ta * g2 - tb * g3;
  grad.segment<3>(6) = g2;
  grad.segment<3>(9) = g3;
  out.gradient = (2 * k * theta) * grad;
  if (what == Derivatives::Hessian) out.hessian = (2 * k) * grad * grad.transpose();
  return out;
}

void add_bending_energy(const SimModel& model, const Eigen::VectorXd& x, EnergyEval& out) {
  const Derivatives what = out.wants_hessian()    ? Derivatives::Hessian
                           : out.wants_gradient() ? Derivatives::Gradient
                                                  : Derivatives::Value;
  for (const BendingHinge& h : model.hinges) {
    const ElementEnergy<4> el = hinge_element_energy(x.segment<3>(3 * h.v[0]), x.segment<3>(3 * h.v[1]),
                                                     x.segment<3>(3 * h.v[2]), x.segment<3>(3 * h.v[3]), h, what);
    out.value += el.value;
    if (what == Derivatives::Value) continue;
    for (int k = 0; k < 4; ++k) out.add_gradient(h.v[k], el.gradient.segment<3>(3 * k));
    if (what == Derivatives::Hessian) out.add_element_hessian<4>(h.v, el.hessian);
  }
}

}  // namespace knitforge
