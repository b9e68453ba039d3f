#pragma once
/// \file simulation_json.h
/// The virtual machine's verdict and the knit-graph comparison as JSON, as
/// `knitforge simulate --json` prints them and the report pages embed them
/// (docs/machines.md, "The simulator").

#include <cstddef>
#include <limits>

#include <nlohmann/json.hpp>

#include "knitforge/machine/knit_graph_compare.h"
#include "knitforge/machine/knitout_simulate.h"

namespace knitforge {

/// {"valid", "machine", "errors", "warnings", "stats": {carriage_passes,
/// knit_passes, transfer_passes, racks, knits, tucks, splits, misses,
/// transfers, fabric_transfers, other_transfers, drops, loops, min_needle,
/// max_needle, time_s, gauge, yarn_mm: {carrier: mm}}, "counts": {category:
/// {errors, warnings}} (categories with findings only), "diagnostics":
/// [{line, severity, rule, check, message}] (at most `max_diagnostics`)}.
nlohmann::json simulation_json(const KnitoutSimulation& sim,
                               size_t max_diagnostics = std::numeric_limits<size_t>::max());

/// {"matches", "map_stitches", "fabric_loops", "mismatches", "issues":
/// [{kind, stitch, row, col, line, message}]}.
nlohmann::json graph_comparison_json(const GraphComparison& comparison);

}  // namespace knitforge
