#include "knitforge/evaluate/shape_error.h"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/util/errors.h"

namespace knitforge {

ShapeError shape_error_to_target(std::span<const Vec3> rest, const StitchMesh& designed, const TriMesh& target,
                                 const SurfaceBvh& bvh, bool refine_with_icp, const IcpOptions& icp_options) {
  if (rest.size() != designed.vertices.size()) {
    throw InvalidInput(fmt::format("shape error: {} rest vertices for a design of {}", rest.size(),
                                   designed.vertices.size()));
  }
  ShapeError ev;
  RigidTransform T = rigid_align(rest, designed.vertices);
  if (refine_with_icp) {
    const IcpResult icp = align_to_surface(rest, bvh, T, icp_options);
    T = icp.transform;
    ev.icp_iterations = icp.iterations;
    ev.icp_converged = icp.converged;
  }
  ev.alignment = T;
  ev.aligned.reserve(rest.size());
  for (const Vec3& p : rest) ev.aligned.push_back(T.apply(p));
  const int nv = static_cast<int>(rest.size());
  double corr = 0;
  for (int v = 0; v < nv; ++v) corr += (ev.aligned[v] - designed.vertices[v]).squaredNorm();
  ev.correspondence_rms = nv > 0 ? std::sqrt(corr / nv) : 0.0;
  ev.target_size = bounding_box(target).diagonal();
  ev.vertex_error.resize(nv);
  double sum2 = 0, dsum2 = 0;
  for (int v = 0; v < nv; ++v) {
    const double e = bvh.closest_point(ev.aligned[v]).distance;
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
  ev.stitch_error.resize(designed.stitches.size());
  for (size_t s = 0; s < designed.stitches.size(); ++s) {
    const Stitch& st = designed.stitches[s];
    double e = 0;
    for (int k = 0; k < st.corners(); ++k) e += ev.vertex_error[st.v[k]];
    ev.stitch_error[s] = e / st.corners();
  }
  return ev;
}

}  // namespace knitforge
