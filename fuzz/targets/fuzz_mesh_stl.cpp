// libFuzzer target: the .stl mesh reader (read_mesh dispatches by extension).
#include "fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return knitforge_fuzz::fuzz_mesh_reader(".stl", data, size);
}
