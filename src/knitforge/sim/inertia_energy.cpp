#include "knitforge/sim/inertia_energy.h"

namespace knitforge {

Eigen::VectorXd predict_positions(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double h_s,
                                  const Vec3& gravity_mm_s2) {
  Eigen::VectorXd xt = x + h_s * v;
  for (Eigen::Index i = 0; i < xt.size() / 3; ++i) xt.segment<3>(3 * i) += h_s * h_s * gravity_mm_s2;
  return xt;
}

void add_inertia_energy(const SimModel& model, const Eigen::VectorXd& x, const Eigen::VectorXd& x_tilde,
                        const Eigen::VectorXd& x_previous, double h_s, EnergyEval& out) {
  const double inv_h2 = 1.0 / (h_s * h_s), inv_h = 1.0 / h_s;
  for (int i = 0; i < model.num_vertices(); ++i) {
    const double m = model.vertex_mass_kg[i] * inv_h2, c = model.vertex_damping_kg_s[i] * inv_h;
    const Vec3 d = x.segment<3>(3 * i) - x_tilde.segment<3>(3 * i);
    const Vec3 dp = x.segment<3>(3 * i) - x_previous.segment<3>(3 * i);
    out.value += 0.5 * (m * d.squaredNorm() + c * dp.squaredNorm());
    if (!out.wants_gradient()) continue;
    out.add_gradient(i, m * d + c * dp);
    if (out.wants_hessian()) out.add_hessian_block(i, i, (m + c) * Mat3::Identity());
  }
}

void add_gravity_energy(const SimModel& model, const Eigen::VectorXd& x, const Vec3& gravity_mm_s2, EnergyEval& out) {
  for (int i = 0; i < model.num_vertices(); ++i) {
    const double m = model.vertex_mass_kg[i];
    out.value -= m * gravity_mm_s2.dot(x.segment<3>(3 * i));
    if (out.wants_gradient()) out.add_gradient(i, -m * gravity_mm_s2);
  }
}

}  // namespace knitforge
