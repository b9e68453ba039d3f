// libFuzzer target: the darts JSON reader (flatten --darts).
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "knitforge/design/flatten/dart_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  knitforge_fuzz::expect_clean([&] {
    (void)knitforge::parse_darts_json(std::string_view(reinterpret_cast<const char*>(data), size),
                                      "fuzz.json", 10.0);
  });
  return 0;
}
