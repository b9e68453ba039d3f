#pragma once
/// \file atomic_file.h
/// Writing output files atomically: the content goes to a temporary file in
/// the same directory, which is renamed over the destination only when the
/// whole content was written. A failed run leaves no half-written file.

#include <functional>
#include <iosfwd>
#include <string>

namespace knitforge {

/// Calls `write(stream)` on a temporary file next to `path`, then renames it
/// to `path`. `binary` opens the stream in binary mode.
/// \throw IOError when the file cannot be created, written or renamed; any
///        exception thrown by `write` is propagated after the temporary file
///        is removed.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write,
                           bool binary = false);

}  // namespace knitforge
