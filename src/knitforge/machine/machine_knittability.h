#pragma once
/// \file machine_knittability.h
/// One knittability truth per machine: can this machine knit this map?
/// (docs/knittability.md, "On a machine"; docs/machines.md.)
///
/// The seed's rules (check_knittability(), convert/map_knittability.h) say
/// whether a map describes a knittable sheet at all. A machine adds its
/// limits: loops per needle when wales end (needle_layout.h), the width of
/// its bed, the floats of a bind-off, its carriers. check_machine_knittability()
/// reports exactly what the machine's program writer (write_knitout() for a
/// two-bed profile, hand_instructions() for a manual one) cannot knit: a
/// map passes it if and only if the writer with the same options produces a
/// program (which, for knitout, the virtual machine accepts and which
/// matches the map).

#include "knitforge/core/knittability.h"
#include "knitforge/core/knitting_map.h"
#include "knitforge/machine/knitout_writer.h"
#include "knitforge/machine/machine_profile.h"

namespace knitforge {

/// The seed's rules, then, when they pass, the machine's: every problem of
/// the needle layout is a `machine-limit` violation naming its map cell
/// (the ending wale's last stitch); any other refusal of the writer (bed
/// width, bind-off float, carriers, options) is a `machine-limit` violation
/// of the whole map (cells empty) with the writer's message.
/// \throw InvalidInput as check_knittability() for inconsistent map arrays.
KnittabilityReport check_machine_knittability(const KnittingMap& map, const MachineProfile& profile,
                                              const KnitoutOptions& options = {},
                                              const KnittabilityOptions& report_options = {});

}  // namespace knitforge
