// libFuzzer target: the stitch mesh PLY reader (per-face stitch properties).
#include "fuzz/fuzz_input.h"
#include "knitforge/io/stitch_mesh_ply.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = knitforge_fuzz::input_path(".ply");
  knitforge_fuzz::write_input(path, data, size);
  knitforge_fuzz::expect_clean([&] { (void)knitforge::read_stitch_mesh_ply(path); });
  return 0;
}
