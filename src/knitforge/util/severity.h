#pragma once
/// \file severity.h
/// How bad a finding is, shared by every checker (knittability of maps and
/// stitch meshes, knitout parsing and simulation).

#include <cstdint>

namespace knitforge {

/// Error: the design or program cannot be knitted (reliably) as it is.
/// Warning: it can, but something is against a convention or the fabric will
/// suffer; a checker's ok() stays true.
enum class Severity : uint8_t { Error = 0, Warning = 1 };

}  // namespace knitforge
