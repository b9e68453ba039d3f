#pragma once
/// \file knit_graph.h
/// KnitGraph: the loops a knitting program makes and how they hang together,
/// as rebuilt by simulate_knitout() (knitout_simulate.h).
///
/// Every loop is formed by one knitout operation (knit, tuck or split, with
/// one or more carriers) and is numbered in formation order, so the loops of
/// one carrier in increasing id are that yarn in order ("yarn order"). A
/// loop's parents are the loops that were on the needle when it was pulled
/// through them (knit, split): in the fabric they are its Bottom (wale)
/// neighbours. A tuck loop has no parents; it is added to the needle and
/// becomes a parent of the next loop knitted there. Transfers move loops
/// between needles and are recorded per loop; drops end a loop's life.
///
/// Sections: comment-only lines mark what the following operations are for
/// (docs/machines.md, "The simulator"): `; cast-on ...`, `; bind-off ...`,
/// `; waste ...` and back to fabric with `; course ...`, `; row ...` or
/// `; fabric ...`. Every loop records the section it was formed in.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "knitforge/machine/knitout_parse.h"

namespace knitforge {

enum class LoopKind : uint8_t {
  Knit = 0,   ///< pulled through the loops on the needle (which dropped)
  Tuck = 1,   ///< added to the needle without pulling through anything
  Split = 2,  ///< pulled through the loops on the needle, which moved to another needle
};

enum class LoopSection : uint8_t { Fabric = 0, CastOn = 1, BindOff = 2, Waste = 3 };

std::string_view name(LoopKind k);
std::string_view name(LoopSection s);

/// One loop of yarn.
struct KnitLoop {
  uint32_t carriers = 0;  ///< bit c set when carrier index c (KnitGraph::carrier_names) forms it
  Needle needle;          ///< the needle it was formed on
  int8_t direction = 1;   ///< carriage direction of the forming operation (+1 / -1)
  LoopKind kind = LoopKind::Knit;
  LoopSection section = LoopSection::Fabric;
  int line = 0;           ///< knitout line of the forming operation
  int pass = -1;          ///< index of the knit pass that formed it (KnitoutSimulation::passes)
  double slot = 0.0;      ///< bed position when formed (front n: n; back n: n + racking)
  int child = -1;         ///< the loop later pulled through this one, -1 when none
  int transfers = 0;      ///< how many times it was moved to another needle
  bool on_empty_needle = false;  ///< the needle held no loop when it was formed
  bool dropped = false;   ///< dropped off its needle by a `drop`
  bool live_at_end = false;  ///< still on a needle when the program ended
  int first_carrier() const;
};

/// One transfer of one loop.
struct KnitTransfer {
  int loop = -1;
  Needle from, to;
  int line = 0;
};

/// The loop graph of a simulated program.
struct KnitGraph {
  std::vector<std::string> carrier_names;  ///< from the program's ;;Carriers:
  std::vector<KnitLoop> loops;             ///< in formation order
  std::vector<int> parent_offsets{0};      ///< CSR: parents of loop i are parents[parent_offsets[i] .. [i+1])
  std::vector<int> parents;
  std::vector<KnitTransfer> transfers;     ///< in program order

  int num_loops() const { return static_cast<int>(loops.size()); }
  /// The loops loop `i` was pulled through, in the order they hung on the needle.
  std::span<const int> parents_of(int i) const {
    return {parents.data() + parent_offsets[i],
            static_cast<size_t>(parent_offsets[i + 1] - parent_offsets[i])};
  }
  /// Appends a loop with the given parents; sets each parent's child. Returns its id.
  /// \pre every parent id is an existing loop
  int add_loop(const KnitLoop& loop, std::span<const int> loop_parents);
};

/// The ids of the loops formed with carrier index `carrier`, in yarn order.
std::vector<int> loops_of_carrier(const KnitGraph& graph, int carrier);

}  // namespace knitforge
