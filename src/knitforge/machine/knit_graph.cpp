#include "knitforge/machine/knit_graph.h"

namespace knitforge {

std::string_view name(LoopKind k) {
  switch (k) {
    case LoopKind::Knit: return "knit";
    case LoopKind::Tuck: return "tuck";
    case LoopKind::Split: return "split";
  }
  return "unknown";
}

std::string_view name(LoopSection s) {
  switch (s) {
    case LoopSection::Fabric: return "fabric";
    case LoopSection::CastOn: return "cast-on";
    case LoopSection::BindOff: return "bind-off";
    case LoopSection::Waste: return "waste";
  }
  return "unknown";
}

int KnitLoop::first_carrier() const {
  for (int c = 0; c < 32; ++c) {
    if (carriers & (1u << c)) return c;
  }
  return -1;
}

int KnitGraph::add_loop(const KnitLoop& loop, std::span<const int> loop_parents) {
  const int id = static_cast<int>(loops.size());
  loops.push_back(loop);
  for (int p : loop_parents) {
    parents.push_back(p);
    loops[p].child = id;
  }
  parent_offsets.push_back(static_cast<int>(parents.size()));
  return id;
}

std::vector<int> loops_of_carrier(const KnitGraph& graph, int carrier) {
  std::vector<int> out;
  if (carrier < 0 || carrier >= 32) return out;
  for (int i = 0; i < graph.num_loops(); ++i) {
    if (graph.loops[i].carriers & (1u << carrier)) out.push_back(i);
  }
  return out;
}

}  // namespace knitforge
