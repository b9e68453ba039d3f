// libFuzzer target: the knitout parser (knitforge simulate's reader).
#include <string_view>

#include "fuzz/fuzz_input.h"
#include "knitforge/machine/knitout_parse.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  knitforge_fuzz::expect_clean(
      [&] { (void)knitforge::parse_knitout(std::string_view(reinterpret_cast<const char*>(data), size)); });
  return 0;
}
