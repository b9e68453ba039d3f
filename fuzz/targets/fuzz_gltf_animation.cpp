// libFuzzer target: the glTF animation reader (cloth bodies, .glb or .gltf by
// content). An accepted file must sample at its start, middle and end to
// one position per vertex, with every face index in range.
#include <cstdlib>

#include "fuzz/fuzz_input.h"
#include "knitforge/io/read_gltf_animation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = knitforge_fuzz::input_path(".glb");
  knitforge_fuzz::write_input(path, data, size);
  knitforge_fuzz::expect_clean([&] {
    const knitforge::GltfAnimatedMesh m = knitforge::read_gltf_animation(path);
    for (const auto& f : m.faces)
      for (int v : f)
        if (v < 0 || v >= m.num_vertices) std::abort();
    for (double t : {m.start_s, 0.5 * (m.start_s + m.end_s), m.end_s}) {
      if (knitforge::gltf_positions_at(m, t).size() != static_cast<size_t>(m.num_vertices)) std::abort();
    }
  });
  return 0;
}
