// libFuzzer target: the polyline OBJ reader (--source polyline:, --cut).
#include "fuzz/fuzz_input.h"
#include "knitforge/io/polyline_obj.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = knitforge_fuzz::input_path(".obj");
  knitforge_fuzz::write_input(path, data, size);
  knitforge_fuzz::expect_clean([&] { (void)knitforge::read_polylines_obj(path); });
  return 0;
}
