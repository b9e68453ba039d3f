#pragma once
// The runners of knitforge-ddr's commands (body_ddr_options.h).

#include "body_ddr_options.h"

namespace knitforge::cli {

int run_ddr_train(const DdrTrainCli& o);
int run_ddr_evaluate(const DdrEvaluateCli& o);
int run_reconstruct(const ReconstructCli& o);

}  // namespace knitforge::cli
