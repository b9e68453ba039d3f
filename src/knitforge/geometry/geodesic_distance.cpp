#include "knitforge/geometry/geodesic_distance.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "knitforge/geometry/geodesic_propagation.h"
#include "knitforge/util/errors.h"

namespace knitforge {

GeodesicSolver::GeodesicSolver(const TriMesh& mesh)
    : geometry_(std::make_unique<detail::GeodesicGeometry>(detail::build_geodesic_geometry(mesh))) {}

GeodesicSolver::~GeodesicSolver() = default;
GeodesicSolver::GeodesicSolver(GeodesicSolver&&) noexcept = default;
GeodesicSolver& GeodesicSolver::operator=(GeodesicSolver&&) noexcept = default;

const TriMesh& GeodesicSolver::mesh() const { return *geometry_->mesh; }

GeodesicField GeodesicSolver::distance(const GeodesicSource& source, const GeodesicOptions& options) const {
  const TriMesh& mesh = *geometry_->mesh;
  bool any = false;
  for (const auto& line : source.polylines) any = any || !line.empty();
  if (!any) throw InvalidInput("geodesic distance: the source has no points");
  const bool sided = options.signed_field && !source.vertex_side.empty();
  if (!source.vertex_side.empty() && static_cast<int>(source.vertex_side.size()) != mesh.num_vertices())
    throw InvalidInput(
        fmt::format("geodesic distance: the source has {} vertex sides but the mesh has {} vertices",
                    source.vertex_side.size(), mesh.num_vertices()));
  detail::GeodesicPropagation prop(*geometry_, false, options.tolerance);
  for (const auto& line : source.polylines) {
    const size_t n = line.size();
    if (n == 0) continue;
    const bool closed =
        n > 2 &&
        (surface_point_position(mesh, line.front()) - surface_point_position(mesh, line.back())).norm() ==
            0.0;
    const size_t npts = closed ? n - 1 : n;
    for (size_t i = 0; i < npts; ++i) {
      std::vector<const SurfacePoint*> nb;
      if (i > 0)
        nb.push_back(&line[i - 1]);
      else if (closed)
        nb.push_back(&line[n - 2]);
      if (i + 1 < n) nb.push_back(&line[i + 1]);
      prop.add_point(line[i], nb);
    }
    for (size_t i = 0; i + 1 < n; ++i) prop.add_segment(line[i], line[i + 1]);
  }
  prop.run();
  GeodesicField field;
  field.distance = prop.distance();
  field.num_windows = prop.num_windows();
  field.is_signed = sided;
  const auto& he = geometry_->he;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (he.is_isolated_vertex(v)) continue;
    double& d = field.distance[v];
    if (!std::isfinite(d))
      throw TopologyError(fmt::format(
          "geodesic distance: vertex {} cannot be reached from the source ({}); the surface has a "
          "component without a source point (check it with `knitforge check`, or remove that part)",
          v, source.description.empty() ? "given source" : source.description));
    if (sided && source.vertex_side[v] < 0) d = -d;
    field.max_abs_distance = std::max(field.max_abs_distance, std::abs(d));
  }
  return field;
}

GeodesicField geodesic_distance(const TriMesh& mesh, const GeodesicSource& source,
                                const GeodesicOptions& options) {
  return GeodesicSolver(mesh).distance(source, options);
}

}  // namespace knitforge
