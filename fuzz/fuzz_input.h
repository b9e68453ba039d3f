#pragma once
// Shared by the libFuzzer targets (docs/fuzzing.md): the readers that take a
// path get the fuzzer's bytes through a file of their own in $TMPDIR (or
// /dev/shm), so the real entry point is exercised; every knitforge::Error is
// an accepted answer to bad input, anything else (another exception, a
// crash, a sanitizer report, a hang, running out of memory) is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "knitforge/io/mesh_io.h"
#include "knitforge/util/errors.h"

namespace knitforge_fuzz {

/// A file name unique to this process, with the given extension (".obj").
inline std::string input_path(const char* extension) {
  const char* dir = std::getenv("TMPDIR");
  std::string base = dir && *dir ? dir : "/dev/shm";
  return base + "/knitforge_fuzz_" + std::to_string(::getpid()) + extension;
}

/// Writes the fuzzer's bytes to `path`.
inline void write_input(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

/// Runs `read`; knitforge errors are fine, any other exception aborts (a finding).
template <class F>
void expect_clean(F&& read) {
  try {
    read();
  } catch (const knitforge::Error&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "knitforge fuzz: unexpected exception: %s\n", e.what());
    std::abort();
  }
}

/// The body of the mesh-reader targets: the bytes as a file with `extension`
/// read by read_mesh(); a mesh that is accepted must have every face index
/// in range.
inline int fuzz_mesh_reader(const char* extension, const uint8_t* data, size_t size) {
  const std::string path = input_path(extension);
  write_input(path, data, size);
  expect_clean([&] {
    const knitforge::TriMesh m = knitforge::read_mesh(path);
    for (const auto& t : m.faces)
      for (int v : t)
        if (v < 0 || v >= m.num_vertices()) std::abort();
  });
  return 0;
}

}  // namespace knitforge_fuzz
