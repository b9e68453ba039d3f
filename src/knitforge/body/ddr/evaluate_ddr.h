#pragma once
/// \file evaluate_ddr.h
/// The seed's evaluation of the DDR network (§5.4.5, Table 5.1) on a
/// held-out synthetic set (test seeds, never trained on: train_ddr.h):
/// EI (eq. 5.10, the mean per-image L1 error of the DDR, normalised units),
/// EP (eq. 5.11, per foreground pixel and channel, in cm) and EG (eq.
/// 5.12, the gradient-domain L1), over the true foreground pixels. EI and EG
/// sum over pixels, so they grow with the image size (the seed's 256 x 256
/// values are not comparable to ours at 64 x 64); EP is.
///
/// And the 3D result a user gets: for `meshes` test pictures, the whole
/// reconstruction (reconstruct_body.h, with its 6 m placement) against the
/// true body: the distance of each reconstructed vertex to the true
/// surface and of each true vertex to the reconstruction (cm; mean and
/// RMS), as placed and after the best translation (closest-point
/// iterations), the latter comparable to the seed's point-to-surface errors.

#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/body/body_model.h"
#include "knitforge/body/ddr/ddr_model.h"

namespace knitforge {

/// Result of evaluate_ddr().
struct DdrEvaluation {
  int samples = 0;
  double ei = 0, ep_cm = 0, eg = 0;   ///< means over the test samples
  /// EP of the flat prediction (both channels at the pelvis depth, 0): what
  /// a network that learnt nothing about depth would score.
  double flat_ep_cm = 0;
  int meshes = 0;
  double placed_mesh_to_body_cm = 0;  ///< mean distance, as placed
  double mesh_to_body_cm = 0;         ///< mean distance after the translation
  double mesh_to_body_rms_cm = 0;
  double body_to_mesh_cm = 0;         ///< mean distance of the true body to the reconstruction (completeness)
  double seconds = 0;
};

/// Evaluates `model` on test samples 0..samples-1 of `body`, and rebuilds
/// `meshes` of them in 3D. \throw InvalidInput for counts below 0 or
/// samples 0.
DdrEvaluation evaluate_ddr(DdrModel& model, const BodyModel& body, int samples, int meshes,
                           const std::function<void(const std::string&)>& log = {});

/// The evaluation as the "evaluation" object of ddr.json.
nlohmann::json ddr_evaluation_json(const DdrEvaluation& e);

}  // namespace knitforge
