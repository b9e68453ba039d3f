#pragma once
/// \file ply_format.h
/// Internal: a generic PLY parser (header + body in ascii, binary little and
/// big endian) and a small record writer, shared by the triangle-mesh PLY
/// reader/writer (ply.h) and the stitch-mesh PLY reader/writer
/// (stitch_mesh_ply.h). Not part of the public interface.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "knitforge/io/io_detail.h"

namespace knitforge::ply_detail {

enum class PlyType : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat : uint8_t { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// Size in bytes of a binary value of type t.
int type_size(PlyType t);
/// True for the six integer types.
bool is_integer(PlyType t);
/// The header name of a type ("uchar", "int", "double", ...).
std::string_view type_name(PlyType t);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  ///< value type (list items for lists)
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;  ///< lists only
};

struct PlyElement {
  std::string name;
  int64_t count = 0;
  std::vector<PlyProperty> properties;
  int64_t header_line = 0;
  /// Index of the property called `name`, or -1.
  int find(std::string_view name) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  size_t body_offset = 0;  ///< first byte after "end_header\n"
  int64_t header_lines = 0;
  /// Index of the element called `name`, or -1.
  int find(std::string_view name) const;
  io_detail::LocKind loc_kind() const {
    return format == PlyFormat::Ascii ? io_detail::LocKind::Line : io_detail::LocKind::Byte;
  }
};

/// Parses and checks the header; also checks that the body can hold the
/// declared element counts (before anything is allocated).
/// \throw IOError with file and line.
PlyHeader read_ply_header(const std::string& path, std::string_view data);

/// One element instance: values[i] is the value of scalar property i (the
/// item count for a list property), lists[i] the items of list property i.
struct PlyRecord {
  std::vector<double> values;
  std::vector<std::vector<double>> lists;
  int64_t loc = 0;  ///< line (ascii) or byte offset (binary) of the record
};

/// Reads every element instance in file order and calls visit(element, record).
/// \throw IOError (file and line / byte offset) for truncated or malformed data.
void read_ply_body(const std::string& path, std::string_view data, const PlyHeader& header,
                   const std::function<void(int, const PlyRecord&)>& visit);

/// Builds a PLY body record by record, ascii or binary little endian.
class PlyWriter {
 public:
  explicit PlyWriter(bool ascii) : ascii_(ascii) {}
  /// Appends a header line (with "\n").
  void header_line(std::string_view line);
  /// Appends one value of type t (value must be representable in t).
  void value(PlyType t, double v);
  /// Ends the current record (newline in ascii).
  void end_record();
  const std::string& data() const { return buf_; }
  bool ascii() const { return ascii_; }

 private:
  bool ascii_;
  bool line_start_ = true;
  std::string buf_;
};

}  // namespace knitforge::ply_detail
