#pragma once
/// \file optimisation_plot.h
/// The history of the short-column optimisation (optimise_boundary.h) as a
/// picture (`optimisation.svg`) and as JSON (`optimisation.json`): the
/// objective (estimated transfer stitches, 3/2 I / sw) of every evaluation
/// against its index, the best so far as a line, projected (eq. 3.9)
/// evaluations as hollow marks, initial designs in grey, the alternatives
/// numbered.

#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/design/shortcolumn/optimise_boundary.h"

namespace knitforge {

/// A self-contained SVG (width x height px) of the history.
/// \throw InvalidInput for an empty history or a size below 200 x 150.
std::string optimisation_plot_svg(const BoundaryOptimisation& opt, int width = 720, int height = 420);

/// The history and result as JSON: {"best": {...}, "evaluations": [{"index",
/// "suggested", "evaluated", "projected", "initial", "region", "metric_mm",
/// "estimated_transfers", "penalised", "best_so_far", "trust_length"}],
/// "alternatives": [...], "regions", "symmetric", "proxy", "seconds"}.
nlohmann::json optimisation_json(const BoundaryOptimisation& opt);

}  // namespace knitforge
