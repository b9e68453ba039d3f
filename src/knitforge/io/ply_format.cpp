#include "knitforge/io/ply_format.h"

#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge::ply_detail {

using namespace io_detail;

namespace {

struct TypeInfo {
  PlyType type;
  std::string_view names[2];
  int size;
  double lo, hi;
};
constexpr TypeInfo kTypes[] = {
    {PlyType::Int8, {"char", "int8"}, 1, -128.0, 127.0},
    {PlyType::UInt8, {"uchar", "uint8"}, 1, 0.0, 255.0},
    {PlyType::Int16, {"short", "int16"}, 2, -32768.0, 32767.0},
    {PlyType::UInt16, {"ushort", "uint16"}, 2, 0.0, 65535.0},
    {PlyType::Int32, {"int", "int32"}, 4, -2147483648.0, 2147483647.0},
    {PlyType::UInt32, {"uint", "uint32"}, 4, 0.0, 4294967295.0},
    {PlyType::Float32, {"float", "float32"}, 4, 0, 0},
    {PlyType::Float64, {"double", "float64"}, 8, 0, 0},
};

bool parse_type(std::string_view s, PlyType& t) {
  for (const auto& info : kTypes) {
    if (s == info.names[0] || s == info.names[1]) {
      t = info.type;
      return true;
    }
  }
  return false;
}

double load_value(const char* p, PlyType t, bool big) {
  switch (t) {
    case PlyType::Int8: return load_scalar<int8_t>(p, big);
    case PlyType::UInt8: return load_scalar<uint8_t>(p, big);
    case PlyType::Int16: return load_scalar<int16_t>(p, big);
    case PlyType::UInt16: return load_scalar<uint16_t>(p, big);
    case PlyType::Int32: return load_scalar<int32_t>(p, big);
    case PlyType::UInt32: return load_scalar<uint32_t>(p, big);
    case PlyType::Float32: return load_scalar<float>(p, big);
    case PlyType::Float64: return load_scalar<double>(p, big);
  }
  return 0;
}

}  // namespace

int type_size(PlyType t) { return kTypes[static_cast<int>(t)].size; }
bool is_integer(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }
std::string_view type_name(PlyType t) { return kTypes[static_cast<int>(t)].names[0]; }

int PlyElement::find(std::string_view n) const {
  for (size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == n) return static_cast<int>(i);
  }
  return -1;
}

int PlyHeader::find(std::string_view n) const {
  for (size_t i = 0; i < elements.size(); ++i) {
    if (elements[i].name == n) return static_cast<int>(i);
  }
  return -1;
}

PlyHeader read_ply_header(const std::string& path, std::string_view data) {
  if (data.empty()) throw IOError(fmt::format("{}: file is empty", path));
  PlyHeader h;
  LineReader lines(data, false);
  std::string_view line;
  std::vector<std::string_view> tok;
  if (!lines.next(line) || trim(line) != "ply") {
    fail_line(path, 1, "not a PLY file: the first line must be 'ply'");
  }
  bool have_format = false, ended = false;
  while (lines.next(line)) {
    const int64_t ln = lines.line_number();
    split_ws(line, tok);
    if (tok.empty() || tok[0] == "comment" || tok[0] == "obj_info") continue;
    if (tok[0] == "format") {
      if (tok.size() < 2) fail_line(path, ln, "'format' needs a format name");
      if (tok[1] == "ascii") h.format = PlyFormat::Ascii;
      else if (tok[1] == "binary_little_endian") h.format = PlyFormat::BinaryLittleEndian;
      else if (tok[1] == "binary_big_endian") h.format = PlyFormat::BinaryBigEndian;
      else {
        fail_line(path, ln, fmt::format("unknown PLY format '{}' (expected ascii, binary_little_endian "
                                        "or binary_big_endian)", tok[1]));
      }
      if (tok.size() != 3 || tok[2] != "1.0") {
        fail_line(path, ln, "the format line must end with the version 1.0 (e.g. 'format ascii 1.0')");
      }
      have_format = true;
    } else if (tok[0] == "element") {
      PlyElement e;
      if (tok.size() != 3 || !parse_int64(tok[2], e.count) || e.count < 0) {
        fail_line(path, ln, "expected 'element <name> <count>' with a non-negative count");
      }
      e.name = std::string(tok[1]);
      e.header_line = ln;
      h.elements.push_back(std::move(e));
    } else if (tok[0] == "property") {
      if (h.elements.empty()) fail_line(path, ln, "'property' before any 'element'");
      PlyProperty p;
      if (tok.size() >= 2 && tok[1] == "list") {
        if (tok.size() != 5) fail_line(path, ln, "expected 'property list <count type> <item type> <name>'");
        if (!parse_type(tok[2], p.count_type) || !parse_type(tok[3], p.type)) {
          fail_line(path, ln, fmt::format("unknown property type in '{}'", trim(line)));
        }
        if (!is_integer(p.count_type)) fail_line(path, ln, "a list count type must be an integer type");
        p.is_list = true;
        p.name = std::string(tok[4]);
      } else {
        if (tok.size() != 3) fail_line(path, ln, "expected 'property <type> <name>'");
        if (!parse_type(tok[1], p.type)) fail_line(path, ln, fmt::format("unknown property type '{}'", tok[1]));
        p.name = std::string(tok[2]);
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (tok[0] == "end_header") {
      ended = true;
      break;
    } else {
      fail_line(path, ln, fmt::format("unexpected header line '{}'", trim(line)));
    }
  }
  if (!ended) fail_line(path, lines.line_number(), "the header has no 'end_header' line (truncated file?)");
  if (!have_format) fail_line(path, lines.line_number(), "the header has no 'format' line");
  h.body_offset = lines.offset();
  h.header_lines = lines.line_number();

  // The smallest body the declared counts need: a value takes at least two
  // characters in ascii ("0 ") and its type size in binary.
  const double remaining = static_cast<double>(data.size() - h.body_offset);
  double need = 0;
  for (const auto& e : h.elements) {
    double per = 0;
    for (const auto& p : e.properties) {
      per += h.format == PlyFormat::Ascii ? 2.0 : type_size(p.is_list ? p.count_type : p.type);
    }
    if (e.properties.empty()) {
      fail_line(path, e.header_line, fmt::format("element '{}' has no properties", e.name));
    }
    need += per * static_cast<double>(e.count);
    if (need - 1 > remaining || e.count > std::numeric_limits<int>::max()) {
      fail_line(path, e.header_line,
                fmt::format("the header declares {} '{}' elements, which need at least {:.0f} bytes, "
                            "but the body has only {:.0f}; the file is truncated or the count is wrong",
                            e.count, e.name, need, remaining));
    }
  }
  return h;
}

void read_ply_body(const std::string& path, std::string_view data, const PlyHeader& h,
                   const std::function<void(int, const PlyRecord&)>& visit) {
  PlyRecord rec;
  if (h.format == PlyFormat::Ascii) {
    LineReader lines(data.substr(h.body_offset), false);
    std::string_view line;
    std::vector<std::string_view> tok;
    for (size_t ei = 0; ei < h.elements.size(); ++ei) {
      const PlyElement& e = h.elements[ei];
      rec.values.assign(e.properties.size(), 0.0);
      rec.lists.resize(e.properties.size());
      for (int64_t i = 0; i < e.count; ++i) {
        do {
          if (!lines.next(line)) {
            fail_line(path, h.header_lines + lines.line_number(),
                      fmt::format("unexpected end of file: element '{}' {} of {} is missing", e.name, i, e.count));
          }
          split_ws(line, tok);
        } while (tok.empty());
        const int64_t ln = h.header_lines + lines.line_number();
        rec.loc = ln;
        size_t t = 0;
        auto next_value = [&](PlyType type, std::string_view what) {
          if (t >= tok.size()) {
            fail_line(path, ln, fmt::format("too few values for element '{}': {} is missing", e.name, what));
          }
          const std::string_view s = tok[t++];
          double v = 0;
          if (is_integer(type)) {
            int64_t iv = 0;
            const auto& info = kTypes[static_cast<int>(type)];
            if (!parse_int64(s, iv) || static_cast<double>(iv) < info.lo || static_cast<double>(iv) > info.hi) {
              fail_line(path, ln, fmt::format("'{}' is not a valid {} value for {}", s, type_name(type), what));
            }
            v = static_cast<double>(iv);
          } else if (!parse_double(s, v)) {
            fail_line(path, ln, fmt::format("'{}' is not a number ({})", s, what));
          } else if (type == PlyType::Float32 && std::isfinite(v)) {
            v = std::abs(v) > std::numeric_limits<float>::max()
                    ? std::copysign(std::numeric_limits<double>::infinity(), v)
                    : static_cast<double>(static_cast<float>(v));
          }
          return v;
        };
        for (size_t p = 0; p < e.properties.size(); ++p) {
          const PlyProperty& prop = e.properties[p];
          if (!prop.is_list) {
            rec.values[p] = next_value(prop.type, prop.name);
            continue;
          }
          const double n = next_value(prop.count_type, prop.name + " count");
          if (n < 0) fail_line(path, ln, fmt::format("negative list length {} for {}", n, prop.name));
          if (n > static_cast<double>(tok.size() - t)) {
            fail_line(path, ln, fmt::format("list '{}' declares {} items but the line has only {}", prop.name,
                                            n, tok.size() - t));
          }
          rec.values[p] = n;
          auto& items = rec.lists[p];
          items.resize(static_cast<size_t>(n));
          for (auto& item : items) item = next_value(prop.type, prop.name);
        }
        if (t != tok.size()) {
          fail_line(path, ln, fmt::format("{} more values than the header declares for element '{}'",
                                          tok.size() - t, e.name));
        }
        visit(static_cast<int>(ei), rec);
      }
    }
    return;
  }
  const bool big = h.format == PlyFormat::BinaryBigEndian;
  size_t pos = h.body_offset;
  for (size_t ei = 0; ei < h.elements.size(); ++ei) {
    const PlyElement& e = h.elements[ei];
    rec.values.assign(e.properties.size(), 0.0);
    rec.lists.resize(e.properties.size());
    for (int64_t i = 0; i < e.count; ++i) {
      rec.loc = static_cast<int64_t>(pos);
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& prop = e.properties[p];
        const PlyType first = prop.is_list ? prop.count_type : prop.type;
        if (data.size() - pos < static_cast<size_t>(type_size(first))) {
          fail_byte(path, static_cast<int64_t>(pos),
                    fmt::format("unexpected end of file in element '{}' {} of {} (property {})", e.name, i,
                                e.count, prop.name));
        }
        const double v = load_value(data.data() + pos, first, big);
        pos += type_size(first);
        rec.values[p] = v;
        if (!prop.is_list) continue;
        if (v < 0) fail_byte(path, rec.loc, fmt::format("negative list length {} for {}", v, prop.name));
        const size_t n = static_cast<size_t>(v);
        if (static_cast<double>(data.size() - pos) < v * type_size(prop.type)) {
          fail_byte(path, static_cast<int64_t>(pos),
                    fmt::format("unexpected end of file in element '{}' {} of {}: list {} has {} items", e.name,
                                i, e.count, prop.name, n));
        }
        auto& items = rec.lists[p];
        items.resize(n);
        for (size_t k = 0; k < n; ++k) {
          items[k] = load_value(data.data() + pos, prop.type, big);
          pos += type_size(prop.type);
        }
      }
      visit(static_cast<int>(ei), rec);
    }
  }
}

void PlyWriter::header_line(std::string_view line) {
  buf_.append(line);
  buf_.push_back('\n');
}

void PlyWriter::value(PlyType t, double v) {
  if (ascii_) {
    if (!line_start_) buf_.push_back(' ');
    line_start_ = false;
    if (is_integer(t)) buf_ += fmt::format("{}", static_cast<int64_t>(v));
    else if (t == PlyType::Float32) buf_ += fmt::format("{}", static_cast<float>(v));
    else buf_ += format_double(v);
    return;
  }
  switch (t) {
    case PlyType::Int8: append_le(buf_, static_cast<int8_t>(v)); break;
    case PlyType::UInt8: append_le(buf_, static_cast<uint8_t>(v)); break;
    case PlyType::Int16: append_le(buf_, static_cast<int16_t>(v)); break;
    case PlyType::UInt16: append_le(buf_, static_cast<uint16_t>(v)); break;
    case PlyType::Int32: append_le(buf_, static_cast<int32_t>(v)); break;
    case PlyType::UInt32: append_le(buf_, static_cast<uint32_t>(v)); break;
    case PlyType::Float32: append_le(buf_, static_cast<float>(v)); break;
    case PlyType::Float64: append_le(buf_, v); break;
  }
}

void PlyWriter::end_record() {
  if (ascii_) buf_.push_back('\n');
  line_start_ = true;
}

}  // namespace knitforge::ply_detail
