// libFuzzer target: the knitting map CSV reader.
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "knitforge/io/knitting_map_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  knitforge_fuzz::expect_clean([&] {
    const knitforge::KnittingMap map = knitforge::knitting_map_from_csv(
        std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.csv");
    // An accepted map writes back and reads back to the same cells.
    const knitforge::KnittingMap again =
        knitforge::knitting_map_from_csv(knitforge::knitting_map_to_csv(map), "again.csv");
    if (again.rows != map.rows || again.cols != map.cols || again.cells != map.cells) std::abort();
  });
  return 0;
}
