#pragma once
/// \file knitout_extensions.h
/// Checking the arguments of a knitout x- extension against what a machine's
/// software accepts (MachineProfile::extensions; docs/machines.md).

#include <string>
#include <string_view>
#include <vector>

#include "knitforge/machine/machine_profile.h"

namespace knitforge {

/// "" when `args` are a value `rule` accepts, else what is wrong with them
/// (one line, e.g. "x-stitch-number takes a number 0-9 or a letter A-Z, not '12'").
std::string extension_value_problem(const ExtensionRule& rule, const std::vector<std::string>& args);

}  // namespace knitforge
