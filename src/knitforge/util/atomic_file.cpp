#include "knitforge/util/atomic_file.h"

#include <cerrno>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write,
                           bool binary) {
  namespace fs = std::filesystem;
  if (path.empty()) throw IOError("cannot write a file with an empty name; give a file name");
  const fs::path target(path);
  {
    std::error_code dir_ec;
    if (fs::is_directory(target, dir_ec)) {
      throw IOError(fmt::format("{}: is a directory; give a file name to write", path));
    }
  }
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = target.parent_path() / fmt::format(".{}.tmp{}.{}", target.filename().string(),
                                                          ::getpid(), counter++);
  {
    std::ofstream out(tmp, binary ? std::ios::out | std::ios::binary | std::ios::trunc
                                  : std::ios::out | std::ios::trunc);
    if (!out) {
      throw IOError(fmt::format("{}: cannot create file ({}); check that the directory exists "
                                "and is writable",
                                path, std::strerror(errno)));
    }
    try {
      write(out);
      out.flush();
    } catch (...) {
      out.close();
      std::error_code ec;
      fs::remove(tmp, ec);
      throw;
    }
    if (!out) {
      out.close();
      std::error_code ec;
      fs::remove(tmp, ec);
      throw IOError(fmt::format("{}: write failed (disk full?)", path));
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();  // before remove() resets ec
    fs::remove(tmp, ec);
    throw IOError(fmt::format("{}: cannot replace file: {}", path, why));
  }
}

}  // namespace knitforge
