#include "knitforge/evaluate/evaluate_stitch_mesh.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/evaluate/surface_distance.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"
#include "knitforge/util/timer.h"

namespace knitforge {

StitchMeshEvaluation evaluate_stitch_mesh(const StitchMesh& designed, const TriMesh& target, const KnitParams& params,
                                          const EvaluateOptions& options) {
  const Timer total;
  if (designed.stitches.empty()) throw InvalidInput("evaluate: the stitch mesh has no stitches");
  if (target.faces.empty()) throw InvalidInput("evaluate: the target surface has no faces");
  StitchMeshEvaluation ev;

  Timer timer;
  RelaxResult relaxed = relax_stitch_mesh(designed, params, options.relax);
  ev.relax_iterations = relaxed.iterations;
  ev.relax_converged = relaxed.converged;
  if (!relaxed.energy.empty()) {
    ev.relax_energy_start = relaxed.energy.front();
    ev.relax_energy_end = relaxed.energy.back();
  }
  ev.seconds.relax = timer.seconds();

  timer.reset();
  const SurfaceBvh bvh(target);
  const std::vector<Vec3>& rest = relaxed.mesh.vertices;
  RigidTransform T = rigid_align(rest, designed.vertices);
  if (options.refine_with_icp) {
    const IcpResult icp = align_to_surface(rest, bvh, T, options.icp);
    T = icp.transform;
    ev.icp_iterations = icp.iterations;
  }
  ev.alignment = T;
  ev.relaxed = std::move(relaxed.mesh);
  for (Vec3& p : ev.relaxed.vertices) p = T.apply(p);
  ev.seconds.align = timer.seconds();

  timer.reset();
  const int nv = ev.relaxed.num_vertices();
  double corr = 0;
  for (int v = 0; v < nv; ++v) corr += (ev.relaxed.vertices[v] - designed.vertices[v]).squaredNorm();
  ev.correspondence_rms = nv > 0 ? std::sqrt(corr / nv) : 0.0;
  ev.target_size = bounding_box(target).diagonal();
  ev.vertex_error.resize(nv);
  double sum2 = 0, dsum2 = 0;
  for (int v = 0; v < nv; ++v) {
    const double e = bvh.closest_point(ev.relaxed.vertices[v]).distance;
    const double d = bvh.closest_point(designed.vertices[v]).distance;
    ev.vertex_error[v] = e;
    sum2 += e * e;
    dsum2 += d * d;
    ev.max_error = std::max(ev.max_error, e);
    ev.designed_max_error = std::max(ev.designed_max_error, d);
  }
  ev.rms_error = nv > 0 ? std::sqrt(sum2 / nv) : 0.0;
  ev.designed_rms_error = nv > 0 ? std::sqrt(dsum2 / nv) : 0.0;
  if (ev.target_size > 0) {
    ev.relative_rms_error = ev.rms_error / ev.target_size;
    ev.relative_max_error = ev.max_error / ev.target_size;
  }
  ev.stitch_error.resize(ev.relaxed.stitches.size());
  for (size_t s = 0; s < ev.relaxed.stitches.size(); ++s) {
    const Stitch& st = ev.relaxed.stitches[s];
    double e = 0;
    for (int k = 0; k < st.corners(); ++k) e += ev.vertex_error[st.v[k]];
    ev.stitch_error[s] = e / st.corners();
  }
  ev.stitch_error_stats = scalar_stats(ev.stitch_error);
  ev.seconds.distance = timer.seconds();

  timer.reset();
  ev.designed_distortion = stitch_distortion(designed, params);
  ev.relaxed_distortion = stitch_distortion(ev.relaxed, params);
  ev.designed_distortion_stats = scalar_stats(distortion_values(ev.designed_distortion));
  ev.relaxed_distortion_stats = scalar_stats(distortion_values(ev.relaxed_distortion));
  ev.seconds.distortion = timer.seconds();
  ev.seconds.total = total.seconds();
  return ev;
}

}  // namespace knitforge
