#pragma once
/// \file knitting_map_csv.h
/// The spreadsheet-editable knitting map (`knitting_map.csv`, docs/formats.md).
///
///     course,dir,0,1,2,3
///     2,>,.,K,K,.
///     1,<,K,K2,K2,K
///     0,>,K,K,K,K
///
/// The header names the columns: `course`, `dir`, then the wale indices
/// 0..cols-1. One line per course follows, the TOP course first, so that a
/// spreadsheet shows the map as drawn (first course at the bottom). Fields:
/// the course index r, the direction `>` (left to right, +1) or `<` (right to
/// left, -1), then one cell code per column: K knit, L short-row left,
/// R short-row right, I increase, D decrease, C collapsed, `.` or an empty
/// field empty. A code may carry a yarn index suffix (`K2`); no suffix means
/// yarn 0.
///
/// A tube (KnittingMap::seam, docs/tubes.md) has a `seam` column after
/// `dir`: the seam line where a closed row (a round) starts, 0..cols-1, or
/// `-` for an open row (a short row on part of the round):
///
///     course,dir,seam,0,1,2,3,4,5
///     1,>,0,K,K,K,K,K,K
///     0,>,0,K,K,K,K,K,K
///
/// Columns 0..cols/2-1 are the front half, cols/2..cols-1 the back half.
/// Sheets have no seam column (their files are unchanged).
///
/// The reader also accepts CRLF line endings, a UTF-8 byte-order mark, spaces
/// around fields, double quotes around a field, lower-case codes, blank lines
/// and `;` as the separator (detected from the header line).

#include <string>
#include <string_view>

#include "knitforge/core/knitting_map.h"

namespace knitforge {

/// The CSV text of `map` (LF line endings).
/// \throw InvalidInput when the map's arrays have inconsistent sizes, a row
///        direction is not ±1, a cell type is unknown, or a yarn index is
///        negative.
std::string knitting_map_to_csv(const KnittingMap& map);

/// Parses CSV text; `source` names the text in messages (usually the path).
/// \throw IOError "<source>:<line>, column <c>: <problem>" for an inconsistent
///        column count, a broken course index sequence, an unknown cell code or
///        direction symbol, or a bad header; "<source>: ..." for an empty text.
KnittingMap knitting_map_from_csv(std::string_view text, const std::string& source);

/// Writes knitting_map_to_csv(map) to `path` atomically.
/// \throw InvalidInput as knitting_map_to_csv(); IOError when writing fails.
void write_knitting_map_csv(const std::string& path, const KnittingMap& map);

/// Reads a map written by write_knitting_map_csv() or edited in a spreadsheet.
/// write then read gives back an equal map (operator==).
/// \throw IOError when the file cannot be read, or as knitting_map_from_csv().
KnittingMap read_knitting_map_csv(const std::string& path);

}  // namespace knitforge
