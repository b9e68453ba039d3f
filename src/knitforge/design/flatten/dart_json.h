#pragma once
/// \file dart_json.h
/// Reading and writing dart specifications as JSON (schema in docs/flatten.md
/// and docs/formats.md, "Darts (JSON)"):
///
///     {"darts": [{"type": "one-end", "orientation": "horizontal",
///                 "to_boundary": false,
///                 "points": [{"vertex": 12}, {"face": 30, "bary": [0.2, 0.3, 0.5]},
///                            {"position": [10.0, 0.0, 55.0]}]}]}
///
/// A top-level array of darts is accepted too. "type" defaults to "one-end",
/// "orientation" to "horizontal", "to_boundary" to false. Positions are in
/// the input mesh's units and multiplied by `position_scale` (to mm).
#include <string>
#include <string_view>
#include <vector>
#include "knitforge/design/flatten/dart.h"

namespace knitforge {

/// Parses darts from JSON text; `source` names the file in messages.
/// \throw InvalidInput naming the source, the dart index and the field for
///        malformed JSON (with the byte offset), unknown keys or values,
///        wrong types, a point that gives none or several of vertex /
///        face+bary / position, or non-finite numbers.
std::vector<DartSpec> parse_darts_json(std::string_view text, const std::string& source,
                                       double position_scale = 1.0);

/// The darts as JSON text in the same schema (positions divided by
/// position_scale), e.g. to save proposed darts for editing.
std::string darts_to_json(const std::vector<DartSpec>& darts, double position_scale = 1.0);

}  // namespace knitforge
