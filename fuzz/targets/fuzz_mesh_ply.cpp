// libFuzzer target: the .ply mesh reader (read_mesh dispatches by extension).
#include "fuzz/fuzz_input.h"
#include "knitforge/io/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = knitforge_fuzz::input_path(".ply");
  knitforge_fuzz::write_input(path, data, size);
  knitforge_fuzz::expect_clean([&] {
    const knitforge::TriMesh m = knitforge::read_mesh(path);
    // A mesh that was accepted must be consistent: every index in range.
    for (const auto& t : m.faces)
      for (int v : t)
        if (v < 0 || v >= m.num_vertices()) std::abort();
  });
  return 0;
}
