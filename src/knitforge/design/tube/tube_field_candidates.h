#pragma once
/// \file tube_field_candidates.h
/// The initial governing fields of seed §3.3.8 (L1562) for the tube route
/// (docs/tubes.md, "Choosing the field"): besides the route's own harmonic
/// field,
///  - `fiedler`: the Fiedler vector of the cotangent Laplacian
///    (geometry/laplacian_eigenvectors.h), the shape's "diameter direction";
///  - `orthogonal`: the field orthogonal to it, "imitating the geodesic
///    distance field on a surface of revolution": the lowest eigenvector of
///    the energy sum_f A_f <grad x, d_f>^2 + kOrthogonalSmoothing x^T L x,
///    d the Fiedler vector's normalised gradient, weighed down where the
///    Fiedler vector is flat (its extrema, where that direction is
///    round-off: flat_weighted_directions(), directional_stiffness()):
///    the smoothest field that changes least along the diameter direction,
///    so its isocurves follow the Fiedler vector's gradient lines. On a
///    surface of revolution these are the meridians, and the field is
///    cos(theta) round the axis: its isocurves are meridians (a
///    transfer-free field when courses follow them, L1560).
///
/// Each candidate is turned into a field the route can knit in rounds, then
/// scored by the divergence metric of that field's normalised gradient
/// (DivergenceMetric::transfer_estimate(): increases + decreases, an
/// estimate); design_tube() knits the lowest-scoring knittable one unless
/// one is forced (TubeFieldKind). What "knittable" means:
///  - an open tube (two rims, each a round: cast on, bound off): the
///    field u with u = 0 on the start rim and 1 on the end rim that follows
///    the candidate's isocurves: it minimises sum_f A_f <grad u, t_f>^2 +
///    kFollowSmoothing u^T L u, t_f the unit tangent of the candidate's
///    isocurve in face f (field_with_level_rims(), directional_stiffness()).
///    Its levels are the candidate's, spaced as a harmonic function spaces
///    them. Knittable when the candidate's two rims are distinct levels of
///    it (no rim vertex differs from its rim's mean by more than kRimSpread
///    of the range) and every level of u is one closed round
///    (round_levels()). The candidate itself would not do: an eigenvector
///    has free (Neumann) rims, so it is flat there (cos(pi z / h) on a
///    cylinder), and the levels beside a rim would be decided by the
///    round-off of the rim's values;
///  - a closed tube (one rim): the candidate gives the crown point, its
///    extreme away from the rim (the sign whose rim mean is below its surface
///    mean, then the largest value); the route's harmonic field is solved
///    from the rim to the crown segment there (tube_crown.h); knittable when
///    that cut succeeds (the point lies far enough from the rim, one crown).
///    `harmonic` takes the point farthest from the rim.
/// The initial field's own estimate (on the input surface) is reported too.

#include <string>
#include <vector>

#include "knitforge/design/tube/tube_field.h"
#include "knitforge/geometry/tri_mesh.h"

namespace knitforge {

/// Which governing field the tube route knits.
enum class TubeFieldKind { Auto, Harmonic, Fiedler, Orthogonal };

/// "auto", "harmonic", "fiedler", "orthogonal".
const char* tube_field_name(TubeFieldKind kind);
/// The kind of a name of tube_field_name().
/// \throw InvalidInput for any other name, listing the names.
TubeFieldKind parse_tube_field(const std::string& name);

/// epsilon of the orthogonal field's energy (see the file comment): small,
/// so that change along the Fiedler gradient dominates; functions of the
/// angle round a tube of radius r and length h win over change along it
/// while epsilon < (pi r / h)^2 (a sock: 0.05).
inline constexpr double kOrthogonalSmoothing = 1e-3;
/// epsilon of the open tube's levelled field (see the file comment): small,
/// so that the candidate's isocurve directions dominate; where they say
/// nothing (a zero gradient) the field is harmonic.
inline constexpr double kFollowSmoothing = 1e-3;
/// A rim is a level of a candidate when no rim vertex lies further than
/// this fraction of the candidate's range from its rim's mean (open tubes).
inline constexpr double kRimSpread = 0.02;

/// The two initial fields on one surface.
struct InitialFields {
  std::vector<double> fiedler, orthogonal;                   ///< one value per vertex (M-unit norm)
  double fiedler_eigenvalue = 0, orthogonal_eigenvalue = 0;  ///< 1/mm^2
  double orthogonal_alignment = 0;  ///< its gradient_alignment() with the Fiedler vector
  bool converged = false;           ///< the eigen-solver's
};

/// The Fiedler vector and the field orthogonal to it (see the file comment).
/// \throw as laplacian_eigenvectors().
InitialFields initial_fields(const TriMesh& surface);

/// An open tube's candidate `f` (one value per vertex) as a field the route
/// can knit in rounds: 0 on `harmonic`'s start loop, 1 on its end loop,
/// following f's isocurves (see the file comment).
/// \throw InvalidInput when f or harmonic has not one value per vertex, f's
///        rims lie on one level, or a rim is not a level of f (naming how
///        far off); SolverError from the solve.
TubeField levelled_field(const TriMesh& mesh, const std::vector<double>& f, const TubeField& harmonic);

/// A candidate as the route measured it.
struct TubeFieldCandidate {
  TubeFieldKind kind = TubeFieldKind::Harmonic;
  double initial_estimate = 0;  ///< transfer estimate of the initial field itself on the input surface
  bool knittable = false;
  std::string why_not;  ///< when not knittable
  double estimate = 0;  ///< transfer estimate of the field knitted (knittable only)
};

}  // namespace knitforge
