#pragma once
/// \file knittability_json.h
/// The JSON form of a knittability report (core/knittability.h), as it
/// appears in report.json and in the CLI's `check --json` output:
///
///     {
///       "knittable": true | false,          // KnittabilityReport::ok()
///       "errors": n, "warnings": n,         // all violations, listed or not
///       "omitted": n,                       // violations left out of the list
///       "violations": [
///         { "rule": "cyclic-row",           // rule_id()
///           "severity": "error" | "warning",
///           "message": "...",
///           "stitches": [int, ...],         // stitch indices (may be empty)
///           "cells": [[row, col], ...],     // map cells / (course, wale); col -1 = whole row
///           "position": [x, y, z] }         // mm
///       ],
///       "counts": { "cyclic-row": n, ... }  // every rule with n > 0
///     }
///
/// nlohmann::json keeps keys sorted, so dump() is byte-identical for the same
/// report.

#include <nlohmann/json.hpp>

#include "knitforge/core/knittability.h"

namespace knitforge {

/// The report as JSON (see the file comment).
nlohmann::json to_json(const KnittabilityReport& report);

/// Reads back what to_json() wrote.
/// \throw IOError naming the key when a key is missing or has the wrong
///        type, or a rule id is unknown.
KnittabilityReport knittability_report_from_json(const nlohmann::json& j);

}  // namespace knitforge
