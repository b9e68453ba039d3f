#include "knitforge/design/tube/tube_field_candidates.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "knitforge/geometry/isocurves.h"
#include "knitforge/geometry/laplacian_eigenvectors.h"
#include "knitforge/util/errors.h"

namespace knitforge {

const char* tube_field_name(TubeFieldKind kind) {
  switch (kind) {
    case TubeFieldKind::Auto:
      return "auto";
    case TubeFieldKind::Harmonic:
      return "harmonic";
    case TubeFieldKind::Fiedler:
      return "fiedler";
    case TubeFieldKind::Orthogonal:
      return "orthogonal";
  }
  return "auto";
}

TubeFieldKind parse_tube_field(const std::string& name) {
  for (TubeFieldKind k :
       {TubeFieldKind::Auto, TubeFieldKind::Harmonic, TubeFieldKind::Fiedler, TubeFieldKind::Orthogonal})
    if (name == tube_field_name(k)) return k;
  throw InvalidInput(fmt::format(
      "tube field '{}' is not one of auto (the lowest-scoring knittable one), harmonic, fiedler, orthogonal",
      name));
}

InitialFields initial_fields(const TriMesh& surface) {
  const LaplacianEigenvectors e = laplacian_eigenvectors(surface, {});
  InitialFields out;
  out.fiedler = e.vectors.front();
  out.fiedler_eigenvalue = e.values.front();
  const LaplacianEigenvectors o = stiffness_eigenvectors(
      surface, directional_stiffness(surface, flat_weighted_directions(surface, out.fiedler, false),
                                     kOrthogonalSmoothing),
      {});
  out.converged = e.converged && o.converged;
  out.orthogonal = o.vectors.front();
  out.orthogonal_eigenvalue = o.values.front();
  out.orthogonal_alignment = gradient_alignment(surface, out.fiedler, out.orthogonal);
  return out;
}

TubeField levelled_field(const TriMesh& mesh, const std::vector<double>& f, const TubeField& harmonic) {
  if (f.size() != mesh.vertices.size() || harmonic.value.size() != mesh.vertices.size())
    throw InvalidInput(fmt::format("tube field candidate: {} values and a field of {} for {} vertices", f.size(),
                                   harmonic.value.size(), mesh.vertices.size()));
  auto mean = [&](const std::vector<int>& loop) {
    double m = 0.0;
    for (int v : loop) m += f[static_cast<size_t>(v)];
    return m / static_cast<double>(loop.size());
  };
  const double a = mean(harmonic.start_loop), b = mean(harmonic.end_loop);
  const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
  const double range = *hi - *lo;
  if (!(std::abs(b - a) > kRimSpread * range))
    throw InvalidInput("its two rims lie on the same level (it runs round the tube, not along it)");
  double spread = 0.0;
  for (const auto* loop : {&harmonic.start_loop, &harmonic.end_loop})
    for (int v : *loop)
      spread = std::max(spread, std::abs(f[static_cast<size_t>(v)] - (loop == &harmonic.start_loop ? a : b)));
  if (spread > kRimSpread * range)
    throw InvalidInput(
        fmt::format("its rims are not levels of it (a rim vertex lies {:.1f} % of its range off its rim's "
                    "mean, more than {:.0f} %)",
                    100.0 * spread / range, 100.0 * kRimSpread));
  // Where the candidate is flat (beside a free rim) its isocurves are
  // round-off: flat_weighted_directions() leaves the field harmonic there.
  return field_with_level_rims(
      mesh, directional_stiffness(mesh, flat_weighted_directions(mesh, f, true), kFollowSmoothing), harmonic);
}

}  // namespace knitforge
