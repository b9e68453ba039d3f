#pragma once
/// \file train_ddr.h
/// Training of the single-image reconstruction (seed §5.4.5) on this CPU,
/// from synthetic samples of our body model (body/ddr_sample.h):
///
/// 1. the cGAN: per batch, one Adam step of the PatchGAN discriminator on
///    -(log D(x1, y) + log(1 - D(x1, G(x)))), then one of the generator on
///    -log D(x1, G(x)) + λ1 L_L1 + λ2 L_∇ (ddr_losses.h);
/// 2. the view-based refinement U-Net, after the generator: its inputs are
///    the generator's own predictions turned by ±45° and ±135° (as the seed
///    prepares them, "after the DDR prediction network is ready"), its
///    target the true min-depth from that view; loss λ1 L_L1 + λ2 L_∇.
///
/// As the seed: Adam (β = 0.5, 0.999), batch 4, the learning rate 1e-4 for
/// the first half of the epochs and 1e-5 for the rest. Unlike the seed
/// (256 x 256, w = 64, 10^4 models, 4 epochs on a GPU), the defaults are
/// 64 x 64, w = 32 and 2,000 bodies: a CPU run of minutes, whose accuracy
/// docs/bodies.md reports. Samples i = 1..N are the training set; the test
/// set (evaluate_ddr.h) uses other seeds, so the two never share a body.
/// Deterministic for the same options and thread count.

#include <cstdint>
#include <functional>
#include <string>

#include "knitforge/body/body_model.h"
#include "knitforge/body/ddr/ddr_model.h"

namespace knitforge {

/// Options of train_ddr().
struct DdrTrainOptions {
  int size = 64;                ///< image side (power of two, 16..256)
  int width = 32;               ///< U-Net / PatchGAN first-layer filters (1..64)
  int samples = 4000;           ///< training bodies
  int epochs = 4;               ///< cGAN epochs
  int refine_epochs = 1;        ///< refinement epochs (each sample once, from one of the four views in turn)
  int batch = 4;
  /// Adam's learning rate, then /10 for the second half of the epochs. The
  /// seed's 1e-4 learns too little in the few thousand steps a CPU run takes
  /// (docs/bodies.md: EP 22 cm after 1000 steps, against 10 cm at 1e-3).
  double learning_rate = 1e-3;
  double max_azimuth_deg = 90;  ///< views drawn in ±this
  uint64_t seed = 1;
  /// Progress lines (may be empty).
  std::function<void(const std::string&)> log;
};

/// Estimated CPU seconds of a training run on this 2-core machine (fitted
/// to measured runs: docs/bodies.md), used to refuse runs beyond a limit.
double estimate_ddr_training_seconds(const DdrTrainOptions& options);

/// Trains a model on `body` (our generated model or any of its form).
/// The returned info.training records the options, the last epoch's mean
/// losses, the steps and the wall time.
/// \throw InvalidInput for options out of range (named).
DdrModel train_ddr(const BodyModel& body, const DdrTrainOptions& options);

}  // namespace knitforge
