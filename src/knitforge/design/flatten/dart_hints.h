#pragma once
/// \file dart_hints.h
/// Where to put darts (seed §2.2.1 and §2.3.1: "different types of darts are
/// added to regions with large distortion; the shapes with darts will be
/// flattened again"): proposals from the distortion of a flattening, and the
/// automatic loop that adds them while the distortion goes down.
///
/// Which type: with s = log σ1 + log σ2 (log of the area scale) per face,
/// a dome flattens with its inside compressed and its boundary stretched
/// (area-weighted mean of s over the faces touching the boundary above the
/// mean over the others): a one-end dart, from the boundary point where the
/// stretching (smoothed over its 2-ring) is largest towards the centre of
/// compression (the compressed vertices' pattern positions weighted by
/// compression and area), `depth` of the way (in the pattern). A saddle has
/// its inside stretched: a two-end dart through the most stretched inner
/// vertex, across the local stretch direction (so the dart opens along it),
/// `length` of the pattern's size, kept `margin` inside the boundary.
/// Orientation: horizontal when the dart runs more along the pattern's x
/// than along y (it is then closed by short rows), vertical otherwise.
/// Candidates within `exclusion` of an earlier dart are skipped.
#include <optional>
#include <string>
#include <vector>
#include "knitforge/design/flatten/dart.h"
#include "knitforge/design/flatten/flatten_surface.h"

namespace knitforge {

struct DartHintOptions {
  double depth = 0.6;       ///< one-end: tip at this fraction of the way to the compressed centre
  double length = 0.3;      ///< two-end: length as a fraction of the pattern's bounding-box diagonal
  double exclusion = 0.15;  ///< skip points closer than this fraction of the surface size to earlier darts
  /// add_darts_automatically(): keep a dart only when it lowers the largest
  /// distortion (at stitch scale) as well as the RMS. false: the RMS alone
  /// decides (a dome's darts then concentrate distortion at their tips).
  bool require_lower_maximum = true;
};

/// A proposed dart and why.
struct DartHint {
  DartSpec spec;       ///< waypoints as 3D positions (mm)
  double score = 0.0;  ///< the smoothed log area scale at the chosen point
  std::string reason;  ///< one sentence for reports
};

/// One dart for flattening `f` (of the mesh f.mesh), or nothing when no
/// candidate is left (all excluded, or no region to cut).
/// \throw InvalidInput for options outside (0, 1).
std::optional<DartHint> propose_dart(const Flattening& f, const DartHintOptions& options = {});

/// The result of add_darts_automatically().
struct AutoDarts {
  std::vector<DartSpec> darts;  ///< the given darts followed by the added ones
  std::vector<DartHint> added;  ///< the hints that were accepted, in order
  /// RMS log singular value (DistortionStats::rms_log_sigma) after the given
  /// darts, then after each accepted dart: strictly decreasing.
  std::vector<double> rms_sequence;
  /// The largest |log σ| at stitch scale (Flattening::stitch_max_abs_log_sigma)
  /// at the same steps: strictly decreasing too.
  std::vector<double> max_sequence;
  Flattening flattening;    ///< with all accepted darts
  std::string stop_reason;  ///< why the loop ended
};

/// Starting from `darts`, proposes and adds up to `max_darts` darts, each
/// kept only when it lowers both the RMS and the maximum distortion (at
/// stitch scale: a dart's tip concentrates distortion, so on a dome such as
/// the hemisphere a single dart raises the maximum and is not kept, unless
/// hint_options.require_lower_maximum is off) and can
/// be cut and flattened without a fold (a dart that does not is rejected and
/// the loop ends, saying why in stop_reason).
/// The angle limit (options.enforce_dart_angle) is checked for the given
/// darts first and for all darts at the end (a single dart may be too wide
/// where the next ones share the opening).
/// \throw as flatten_surface() for the given darts; InvalidInput when
///        max_darts < 0, or when a dart is wider than its limit at the end
///        and options.enforce_dart_angle (names the dart and its angle).
AutoDarts add_darts_automatically(const TriMesh& mesh, const std::vector<DartSpec>& darts, int max_darts,
                                  const FlattenOptions& options = {},
                                  const DartHintOptions& hint_options = {});

}  // namespace knitforge
