#pragma once
/// \file io_detail.h
/// Internal helpers shared by the readers and writers of the io module: whole
/// file loading, line iteration with line numbers, number parsing, byte-order
/// conversion, error messages that name the file and the line (or byte
/// offset), and the final connectivity check of a triangle mesh read from a
/// file. Not part of the public interface.

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge::io_detail {

/// The whole content of `path`.
/// \throw IOError when the file does not exist or cannot be read.
std::string load_file(const std::string& path);

/// Lower-case extension of `path` without the dot ("obj"), "" when none.
std::string extension(const std::string& path);

/// Whether a location counts text lines (1-based) or bytes from the start.
enum class LocKind : uint8_t { Line, Byte };

/// "path:12: " for lines, "path: byte 345: " for byte offsets.
std::string where(const std::string& path, LocKind kind, int64_t loc);

/// `message` with every quoted span ('...', input echoed back) cut to 80
/// characters ("... (N more characters)") and every byte that is not
/// printable ASCII replaced by '?': messages quote input, never dump it.
std::string printable_message(std::string_view message);

/// Throws IOError("path:line: message") (message as printable_message()).
[[noreturn]] void fail_line(const std::string& path, int64_t line, std::string_view message);
/// Throws IOError("path: byte N: message") (message as printable_message()).
[[noreturn]] void fail_byte(const std::string& path, int64_t offset, std::string_view message);

/// Iterates over the lines of a text, with 1-based line numbers. Strips "\r"
/// before "\n" and a UTF-8 byte-order mark at the start of the text.
class LineReader {
 public:
  explicit LineReader(std::string_view text, bool strip_bom = true);
  /// Next line (without terminator); false at the end of the text.
  bool next(std::string_view& line);
  /// Number of the line last returned by next() (0 before the first).
  int64_t line_number() const { return line_; }
  /// Byte offset just past the terminator of the last returned line.
  size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  int64_t line_ = 0;
};

/// Splits at runs of spaces and tabs; no empty tokens.
std::vector<std::string_view> split_ws(std::string_view s);
/// Same, into an existing vector (cleared first).
void split_ws(std::string_view s, std::vector<std::string_view>& out);
/// Removes leading and trailing spaces, tabs, "\r" and "\n".
std::string_view trim(std::string_view s);
/// `s` with everything from the first '#' removed.
std::string_view strip_comment(std::string_view s);

/// Parses the whole token as a double (a leading '+' is allowed); false on
/// junk. NaN and infinities parse (callers check finiteness).
bool parse_double(std::string_view s, double& out);
/// Parses the whole token as a decimal integer (a leading '+' allowed).
bool parse_int64(std::string_view s, int64_t& out);

/// True when the machine stores numbers little-endian.
bool host_little_endian();

/// Reads a T stored with the given byte order at `p`.
template <class T>
T load_scalar(const char* p, bool big_endian) {
  char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (big_endian == host_little_endian()) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

/// Appends the bytes of v in little-endian order.
template <class T>
void append_le(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (!host_little_endian()) {
    for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  out.append(b, sizeof(T));
}

/// Shortest-exact text of a double ("%.17g"-equivalent round trip).
std::string format_double(double v);

/// Final step of every mesh reader: rejects a mesh without faces, then builds
/// the half-edge connectivity and rethrows its TopologyError as IOError with
/// the location (face_loc[f], a line or a byte offset) of the face involved,
/// e.g. "shirt.obj:1234: edge (5, 9) is shared by 3 faces ...".
/// \throw IOError as described.
void check_mesh(const std::string& path, const TriMesh& mesh, const std::vector<int64_t>& face_loc,
                LocKind kind);

/// The same connectivity check for a polygon mesh in compressed form (see
/// build_halfedges); does not require faces.
void check_polygon_mesh(const std::string& path, int num_vertices, const std::vector<int>& face_start,
                        const std::vector<int>& face_vertices, const std::vector<int64_t>& face_loc,
                        LocKind kind);

/// Checks a mesh and writer options before writing `format` ("OBJ", ...):
/// indices in range, finite coordinates, colour arrays empty or of the right
/// size and supported by the format.
/// \throw InvalidInput naming `path` and the offending element.
void check_mesh_for_writing(const std::string& path, const TriMesh& mesh,
                            const MeshWriteOptions& options, std::string_view format,
                            bool vertex_colours_supported, bool face_colours_supported);

}  // namespace knitforge::io_detail
