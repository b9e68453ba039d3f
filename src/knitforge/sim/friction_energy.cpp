#include "knitforge/sim/friction_energy.h"

#include <cmath>

namespace knitforge {

std::vector<FrictionPair> build_friction_pairs(const SimModel& model, const std::vector<ContactPair>& contacts,
                                               const KinematicBody& body_start, const KinematicBody& body_end,
                                               const Eigen::VectorXd& x_lag, const ContactParams& params) {
  std::vector<FrictionPair> out;
  if (params.friction <= 0) return out;
  for (const ContactPair& c : contacts) {
    const Vec3 x = x_lag.segment<3>(3 * c.vertex);
    const PairBarrier b = pair_barrier(x, c, body_start, model.vertex_area_mm2[c.vertex], params);
    if (!(b.normal_force_mn > 0)) continue;
    FrictionPair f;
    f.vertex = c.vertex;
    f.face = c.body.face;
    f.part = c.body.part;
    f.bary = c.body.where.bary;
    f.normal_force_mn = b.normal_force_mn;
    Vec3 n = x - c.body.where.point;
    n = n.norm() > 0 ? Vec3(n.normalized()) : body_start.face_normal(c.body.face);
    // Any orthonormal pair perpendicular to n (deterministic).
    const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 t0 = n.cross(a).normalized();
    f.tangent.col(0) = t0;
    f.tangent.col(1) = n.cross(t0);
    f.body_motion = body_end.point(f.face, f.bary) - body_start.point(f.face, f.bary);
    out.push_back(f);
  }
  return out;
}

void add_friction_energy(const std::vector<FrictionPair>& pairs, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& x_start, double h_s, const ContactParams& params, EnergyEval& out) {
  const double eps = params.friction_velocity_mm_s * h_s;
  for (const FrictionPair& p : pairs) {
    const Vec3 dx = x.segment<3>(3 * p.vertex) - x_start.segment<3>(3 * p.vertex) - p.body_motion;
    const Eigen::Vector2d u = p.tangent.transpose() * dx;
    const double y = u.norm();
    const double k = params.friction * p.normal_force_mn;
    double F, F1_over_y, F2;
    if (y < eps) {
      F = -y * y * y / (3 * eps * eps) + y * y / eps + eps / 3;
      F1_over_y = -y / (eps * eps) + 2 / eps;
      F2 = -2 * y / (eps * eps) + 2 / eps;
    } else {
      F = y;
      F1_over_y = 1 / y;
      F2 = 0;
    }
    out.value += k * F;
    if (!out.wants_gradient()) continue;
    // F'(y) û = (F'(y)/y) u, well defined at u = 0.
    out.add_gradient(p.vertex, k * F1_over_y * (p.tangent * u));
    if (!out.wants_hessian()) continue;
    Eigen::Matrix2d h2 = F1_over_y * Eigen::Matrix2d::Identity();
    if (y > 0) {
      const Eigen::Vector2d uh = u / y;
      h2 += (F2 - F1_over_y) * uh * uh.transpose();
    }
    out.add_hessian_block(p.vertex, p.vertex, k * p.tangent * h2 * p.tangent.transpose());
  }
}

}  // namespace knitforge
