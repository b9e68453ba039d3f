#pragma once
// The options of `knitforge body ddr-train | ddr-evaluate | reconstruct`
// (single-image reconstruction, seed §5.4), shared by the two programs:
// knitforge registers them (so its help lists them and parses them) and
// hands the command line to knitforge-ddr, which registers the same options
// and runs them with LibTorch.

#include <cstdint>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli_common.h"

namespace knitforge::cli {

struct DdrTrainCli {
  std::string outdir;
  int size = 64;
  int width = 32;
  int samples = 4000;
  int epochs = 4;
  int refine_epochs = 1;
  int test_samples = 100;
  int test_meshes = 5;
  double learning_rate = 1e-3;
  double max_azimuth = 90;
  uint64_t seed = 1;
  int threads = 2;
  double max_hours = 2;
};

struct DdrEvaluateCli {
  std::string model;
  int samples = 100;
  int meshes = 5;
  bool update = false;
  bool json = false;
};

struct ReconstructCli {
  std::string image;
  std::string keypoints;
  std::string model;
  std::string output;
  std::string ddr_png;
  bool no_refine = false;
  uint64_t seed = 1;
};

/// What choosing each command does.
struct DdrRunners {
  std::function<int(const DdrTrainCli&)> train;
  std::function<int(const DdrEvaluateCli&)> evaluate;
  std::function<int(const ReconstructCli&)> reconstruct;
};

/// Registers the three commands on `body`.
void add_body_ddr_commands(CLI::App& body, Action& action, const DdrRunners& runners);

}  // namespace knitforge::cli
