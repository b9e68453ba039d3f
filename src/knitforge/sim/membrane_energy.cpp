#include "knitforge/sim/membrane_energy.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace knitforge {

namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// Energy density W(F) per rest area and its F-space derivatives
// (F stacked as [f_c; f_w]).
struct DensityEval {
  double w = 0.0;
  Vec6 dw = Vec6::Zero();
  Mat6 d2w = Mat6::Zero();
  double tc = 0.0, tw = 0.0, ts = 0.0;  // ∂W/∂ε_c, ∂W/∂ε_w, ∂W/∂γ
  double ec = 0.0, ew = 0.0, g = 0.0;
};

DensityEval density(const Vec3& fc, const Vec3& fw, const KnitMaterial& m, Derivatives what) {
  DensityEval d;
  const double lc = fc.norm(), lw = fw.norm();
  d.ec = lc - 1.0;
  d.ew = lw - 1.0;
  d.g = fc.dot(fw);
  const double c12 = m.poisson_course_wale * m.wale.initial_stiffness();
  const CurveValue pc = evaluate_curve(m.course, d.ec);
  const CurveValue pw = evaluate_curve(m.wale, d.ew);
  const CurveValue ps = evaluate_curve(m.shear, d.g, true);
  d.w = pc.energy + pw.energy + c12 * d.ec * d.ew + ps.energy;
  d.tc = pc.tension + c12 * d.ew;
  d.tw = pw.tension + c12 * d.ec;
  d.ts = ps.tension;
  if (what == Derivatives::Value) return d;
  // Unit directions; a collapsed line element (|f| = 0) has none, and
  // contributes no direction-dependent terms.
  constexpr double kTiny = 1e-12;
  const Vec3 uc = lc > kTiny ? Vec3(fc / lc) : Vec3::Zero();
  const Vec3 uw = lw > kTiny ? Vec3(fw / lw) : Vec3::Zero();
  d.dw.head<3>() = d.tc * uc + d.ts * fw;
  d.dw.tail<3>() = d.tw * uw + d.ts * fc;
  if (what != Derivatives::Hessian) return d;
  const Mat3 I = Mat3::Identity();
  const Mat3 Pc = I - uc * uc.transpose(), Pw = I - uw * uw.transpose();
  d.d2w.topLeftCorner<3, 3>() =
      pc.slope * uc * uc.transpose() + (d.tc / std::max(lc, kTiny)) * Pc + ps.slope * fw * fw.transpose();
  d.d2w.bottomRightCorner<3, 3>() =
      pw.slope * uw * uw.transpose() + (d.tw / std::max(lw, kTiny)) * Pw + ps.slope * fc * fc.transpose();
  const Mat3 cross = c12 * uc * uw.transpose() + ps.slope * fw * fc.transpose() + d.ts * I;
  d.d2w.topRightCorner<3, 3>() = cross;
  d.d2w.bottomLeftCorner<3, 3>() = cross.transpose();
  return d;
}

// dF/dx coefficients: f_a = sum_i c(i, a) x_i.
Eigen::Matrix<double, 3, 2> shape_coefficients(const Mat2& B) {
  Eigen::Matrix<double, 3, 2> c;
  c.row(1) = B.row(0);
  c.row(2) = B.row(1);
  c.row(0) = -B.row(0) - B.row(1);
  return c;
}

}  // namespace

ElementEnergy<3> membrane_element_energy(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                         const MembraneElement& element, const KnitMaterial& material,
                                         Derivatives what, PsdProjection projection) {
  ElementEnergy<3> out;
  const Mat2& B = element.rest_inverse;
  const Vec3 e1 = x1 - x0, e2 = x2 - x0;
  const Vec3 fc = e1 * B(0, 0) + e2 * B(1, 0);
  const Vec3 fw = e1 * B(0, 1) + e2 * B(1, 1);
  DensityEval d = density(fc, fw, material, what);
  const double A = element.rest_area_mm2;
  out.value = A * d.w;
  if (what == Derivatives::Value) return out;
  const Eigen::Matrix<double, 3, 2> c = shape_coefficients(B);
  for (int i = 0; i < 3; ++i) out.gradient.segment<3>(3 * i) = A * (c(i, 0) * d.dw.head<3>() + c(i, 1) * d.dw.tail<3>());
  if (what != Derivatives::Hessian) return out;
  project_psd<6>(d.d2w, projection);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Mat3 blk = Mat3::Zero();
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) blk += (c(i, a) * c(j, b)) * d.d2w.block<3, 3>(3 * a, 3 * b);
      out.hessian.block<3, 3>(3 * i, 3 * j) = A * blk;
    }
  }
  return out;
}

void add_membrane_energy(const SimModel& model, const Eigen::VectorXd& x, PsdProjection projection,
                         EnergyEval& out) {
  add_element_energies<3>(
      model.elements.size(),
      [&](std::size_t i, Derivatives what) {
        const MembraneElement& e = model.elements[i];
        return membrane_element_energy(x.segment<3>(3 * e.v[0]), x.segment<3>(3 * e.v[1]), x.segment<3>(3 * e.v[2]),
                                       e, model.materials[e.material], what, projection);
      },
      [&](std::size_t i) { return model.elements[i].v; }, out);
}

MembraneStress membrane_stress(const Vec3& x0, const Vec3& x1, const Vec3& x2, const MembraneElement& element,
                               const KnitMaterial& material) {
  const Mat2& B = element.rest_inverse;
  const Vec3 e1 = x1 - x0, e2 = x2 - x0;
  const Vec3 fc = e1 * B(0, 0) + e2 * B(1, 0);
  const Vec3 fw = e1 * B(0, 1) + e2 * B(1, 1);
  const DensityEval d = density(fc, fw, material, Derivatives::Gradient);
  MembraneStress s;
  s.course_n_per_m = d.tc;
  s.wale_n_per_m = d.tw;
  s.shear_n_per_m = d.ts;
  s.course_strain = d.ec;
  s.wale_strain = d.ew;
  s.shear_strain = d.g;
  const double J = fc.cross(fw).norm();
  if (J > 1e-12) {
    const Mat3 sigma = (d.dw.head<3>() * fc.transpose() + d.dw.tail<3>() * fw.transpose()) / J;
    const Mat3 sym = 0.5 * (sigma + sigma.transpose());
    // In-plane principal values: the eigenvalues of σ restricted to the
    // deformed tangent plane (the third, normal one is zero).
    const Vec3 u = fc.normalized();
    const Vec3 v = fc.cross(fw).cross(fc).normalized();
    Eigen::Matrix<double, 3, 2> T;
    T.col(0) = u;
    T.col(1) = v;
    const Mat2 s2 = T.transpose() * sym * T;
    const Eigen::SelfAdjointEigenSolver<Mat2> eig(s2);
    s.principal_min_n_per_m = eig.eigenvalues()[0];
    s.principal_max_n_per_m = eig.eigenvalues()[1];
  }
  // N/m divided by mm is kPa.
  s.principal_max_kpa = s.principal_max_n_per_m / material.thickness_mm;
  return s;
}

}  // namespace knitforge
