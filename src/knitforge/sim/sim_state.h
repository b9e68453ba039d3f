#pragma once
/// \file sim_state.h
/// The state of a simulation: positions and velocities of the fabric's
/// vertices as 3n vectors (x_0, y_0, z_0, x_1, ...), and the time.

#include <Eigen/Core>

namespace knitforge {

struct SimState {
  Eigen::VectorXd positions_mm;
  Eigen::VectorXd velocities_mm_s;
  double time_s = 0.0;
};

}  // namespace knitforge
