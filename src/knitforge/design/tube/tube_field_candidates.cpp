#include "knitforge/design/tube/tube_field_candidates.h"

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
  std::vector<Vec3> d = field_face_gradients(surface, out.fiedler);
  for (Vec3& g : d) g = g.norm() > 0.0 ? Vec3(g / g.norm()) : Vec3(Vec3::Zero());
  const LaplacianEigenvectors o =
      stiffness_eigenvectors(surface, directional_stiffness(surface, d, kOrthogonalSmoothing), {});
  out.converged = e.converged && o.converged;
  out.orthogonal = o.vectors.front();
  out.orthogonal_eigenvalue = o.values.front();
  out.orthogonal_alignment = gradient_alignment(surface, out.fiedler, out.orthogonal);
  return out;
}

}  // namespace knitforge
