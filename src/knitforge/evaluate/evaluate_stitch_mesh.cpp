#include "knitforge/evaluate/evaluate_stitch_mesh.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/evaluate/shape_error.h"
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
  ShapeError se = shape_error_to_target(relaxed.mesh.vertices, designed, target, bvh, options.refine_with_icp,
                                        options.icp);
  ev.icp_iterations = se.icp_iterations;
  ev.alignment = se.alignment;
  ev.relaxed = std::move(relaxed.mesh);
  ev.relaxed.vertices = std::move(se.aligned);
  ev.correspondence_rms = se.correspondence_rms;
  ev.target_size = se.target_size;
  ev.rms_error = se.rms_error;
  ev.max_error = se.max_error;
  ev.relative_rms_error = se.relative_rms_error;
  ev.relative_max_error = se.relative_max_error;
  ev.designed_rms_error = se.designed_rms_error;
  ev.designed_max_error = se.designed_max_error;
  ev.vertex_error = std::move(se.vertex_error);
  ev.stitch_error = std::move(se.stitch_error);
  ev.seconds.align = timer.seconds();
  timer.reset();
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
