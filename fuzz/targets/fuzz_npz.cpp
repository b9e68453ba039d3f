// libFuzzer target: the .npz reader (SMPL-format body models). Every array
// accepted must hold exactly the number of values its shape says.
#include <cstdlib>

#include "fuzz/fuzz_input.h"
#include "knitforge/io/read_npz.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = knitforge_fuzz::input_path(".npz");
  knitforge_fuzz::write_input(path, data, size);
  knitforge_fuzz::expect_clean([&] {
    for (const auto& [name, a] : knitforge::read_npz(path)) {
      const auto n = static_cast<size_t>(a.size());
      if ((a.is_integer ? a.ints.size() : a.doubles.size()) != n) std::abort();
      if (!(a.is_integer ? a.doubles.empty() : a.ints.empty())) std::abort();
    }
  });
  return 0;
}
