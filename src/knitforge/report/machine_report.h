#pragma once
/// \file machine_report.h
/// The machine section of report.json: what a knitter reads first about a
/// design's program (docs/report.md, "For the knitter"; issue 12 item 3).

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "knitforge/core/knit_params.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

/// The knitter's summary of `program` (as write_knitout() returns it, with
/// its verification) for `map` on `profile`, written to `knitout_file`:
///   {"profile", "machine", "gauge", "knitout": file name,
///    "verdict": "VALID" | "INVALID", "matches_map", "errors", "warnings",
///    "stitches", "courses", "wales", "finished_size_mm": [x, y, z] (the
///    bounding box of `designed`, when given), "knit_time_s" (estimate),
///    "yarn_m": [{"carrier", "role": main | waste | draw thread, "metres"}]
///    (estimate), "shaping": {"transfer_stitches" (Increase + Decrease
///    stitches of short columns: what the seed counts, §3.3),
///    "short_column_increases", "short_column_decreases", "wales_started"
///    and "wales_ended" (short columns and the fabric edges), "edge_bound_off"
///    (wales ended by an edge bind-off chain), "transfers" (xfer operations
///    of the fabric), "other_transfers" (cast-on, bind-off, waste)},
///    "short_row_turns": {"inside", "closed",
///    "open"}, "waste_courses", "needles": [first, last], "carriage_passes",
///    "racks", "notes": [...]}.
/// Every figure comes from the program's simulation (the writer's counts
/// when it was not verified).
nlohmann::json machine_report_json(const KnitoutProgram& program, const MachineProfile& profile,
                                   const KnittingMap& map, const std::string& knitout_file,
                                   const StitchMesh* designed = nullptr);

/// The machine section for a design that got no program: {"profile",
/// "machine", "verdict": "NOT WRITTEN", "reason"}.
nlohmann::json machine_report_skipped(const MachineProfile& profile, const std::string& reason);

}  // namespace knitforge
