#pragma once
/// \file vertex_field.h
/// A per-vertex scalar field as a text file (the user's governing field of
/// `knitforge shortcolumn --field FILE`, docs/formats.md): one number per
/// line, in vertex order; empty lines and lines starting with '#' are
/// ignored; a line may hold one number only.

#include <string>
#include <vector>

namespace knitforge {

/// Reads the field; `expected` is the vertex count it must have (< 0: any).
/// \throw IOError naming the file (and line) when it cannot be read, a line
///        is not one finite number, or the count differs from `expected`
///        (the message gives both counts).
std::vector<double> read_vertex_field(const std::string& path, int expected = -1);

/// Writes one value per line (shortest round-trip decimal), atomically.
/// \throw IOError when the file cannot be written; InvalidInput for a
///        non-finite value.
void write_vertex_field(const std::string& path, const std::vector<double>& values);

}  // namespace knitforge
