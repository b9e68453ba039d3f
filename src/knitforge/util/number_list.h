#pragma once
/// \file number_list.h
/// "1,2.5,-3": the comma-separated numbers of a command-line option
/// (--source plane:..., --bc, --mirror).

#include <string>
#include <vector>

namespace knitforge {

/// The numbers of `text`, split at commas; each item must be a whole number
/// literal (std::stod consuming all of it).
/// \throw InvalidInput "<context>: '<item>' is not a number" otherwise.
std::vector<double> parse_number_list(const std::string& text, const std::string& context);

}  // namespace knitforge
