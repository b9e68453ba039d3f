#include "knitforge/sim/contact_energy.h"

#include <cmath>

#include "knitforge/sim/contact_barrier.h"

namespace knitforge {

PairBarrier pair_barrier(const Vec3& x, const ContactPair& pair, const KinematicBody& body, double weight_mm2,
                         const ContactParams& params, PsdProjection projection) {
  PairBarrier out;
  const auto& f = body.mesh().faces[pair.body.face];
  const auto& bv = body.mesh().vertices;
  const TrianglePoint q = closest_triangle_point(x, bv[f[0]], bv[f[1]], bv[f[2]]);
  const Vec3 d = x - q.point;
  const double s = d.squaredNorm();
  const double sh = params.distance_mm * params.distance_mm;
  const BarrierValue b = contact_barrier(s / sh);
  const double K = params.barrier_pressure_kpa * weight_mm2 * params.distance_mm;
  out.value = K * b.b;
  if (!std::isfinite(out.value) || b.db == 0.0) return out;
  // dE/ds = K b' / ŝ; ∇s = 2 d.
  const double dEds = K * b.db / sh, d2Eds2 = K * b.d2b / (sh * sh);
  out.gradient = dEds * 2.0 * d;
  out.normal_force_mn = -dEds * 2.0 * std::sqrt(s);
  Mat3 hs;  // ∇²s
  switch (q.region) {
    case TrianglePoint::Region::Face: {
      const Vec3 n = body.face_normal(pair.body.face);
      hs = 2.0 * n * n.transpose();
      break;
    }
    case TrianglePoint::Region::Edge: {
      const Vec3 t = (bv[f[(q.feature + 1) % 3]] - bv[f[q.feature]]).normalized();
      hs = 2.0 * (Mat3::Identity() - t * t.transpose());
      break;
    }
    case TrianglePoint::Region::Vertex: hs = 2.0 * Mat3::Identity(); break;
  }
  out.hessian = d2Eds2 * 4.0 * d * d.transpose() + dEds * hs;
  project_psd<3>(out.hessian, projection);
  return out;
}

void add_contact_energy(const SimModel& model, const std::vector<ContactPair>& pairs, const KinematicBody& body,
                        const Eigen::VectorXd& x, const ContactParams& params, EnergyEval& out) {
  for (const ContactPair& p : pairs) {
    const PairBarrier b = pair_barrier(x.segment<3>(3 * p.vertex), p, body, model.vertex_area_mm2[p.vertex], params);
    out.value += b.value;
    if (!std::isfinite(out.value)) return;
    if (!out.wants_gradient()) continue;
    out.add_gradient(p.vertex, b.gradient);
    if (out.wants_hessian()) out.add_hessian_block(p.vertex, p.vertex, b.hessian);
  }
}

}  // namespace knitforge
