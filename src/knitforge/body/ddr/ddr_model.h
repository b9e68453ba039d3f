#pragma once
/// \file ddr_model.h
/// A trained single-image reconstruction model (seed §5.4) and its
/// directory: `ddr.json` (what the networks are: image size, width, the
/// camera and normalisation they were trained for; how they were trained
/// and evaluated), `generator.pt` (the DDR prediction U-Net, 21 -> 2
/// channels) and `refiner.pt` (the view-based refinement U-Net, 19 -> 1),
/// LibTorch archives. `knitforge body ddr-train` writes one; `knitforge body
/// reconstruct` and `ddr-evaluate` read it. No model ships with knitforge:
/// it is trained here, from our own synthetic bodies.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knitforge/body/ddr/unet_generator.h"

namespace knitforge {

/// What a model is.
struct DdrModelInfo {
  int size = 64;                 ///< image side (pixels)
  int width = 32;                ///< U-Net first-layer filters
  double max_azimuth_deg = 90;   ///< the views it was trained on
  nlohmann::json training;       ///< options, losses, time (free form, written by train_ddr)
  nlohmann::json evaluation;     ///< EI, EP, EG and 3D errors (evaluate_ddr)
};

/// A model in memory.
struct DdrModel {
  DdrModelInfo info;
  UNetGenerator generator{nullptr};
  UNetGenerator refiner{nullptr};
};

/// Fresh (untrained, seeded) networks for `info`.
/// \throw InvalidInput as UNetGenerator.
DdrModel make_ddr_model(const DdrModelInfo& info, uint64_t seed);

/// Writes the model directory (created if missing; each file written to a
/// temporary name and renamed, so a failed run leaves no half-written file).
/// \throw IOError naming the file.
void save_ddr_model(const std::string& dir, const DdrModel& model);

/// Reads a model directory.
/// \throw IOError naming the file: missing, not a model of this format, or
///        networks that do not match ddr.json.
DdrModel load_ddr_model(const std::string& dir);

/// The generator's DDR (2 x s x s, normalised) for one 21-channel input
/// (3 RGB in [0, 1], 18 heatmaps); BatchNorm in eval mode, dropout on with
/// torch seeded by `seed` (deterministic).
std::vector<float> predict_ddr(DdrModel& model, const std::vector<float>& input, uint64_t seed);

/// The refiner's min-depth (s x s, normalised) for one 19-channel input.
std::vector<float> predict_view(DdrModel& model, const std::vector<float>& input, uint64_t seed);

}  // namespace knitforge
