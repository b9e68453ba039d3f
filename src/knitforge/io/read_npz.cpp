#include "knitforge/io/read_npz.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <filesystem>
#include <fstream>
#include <limits>

#include <fmt/core.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/util/errors.h"

namespace knitforge {

using namespace io_detail;

namespace {

constexpr uint32_t kLocalSig = 0x04034b50, kCentralSig = 0x02014b50, kEndSig = 0x06054b50;
constexpr uint32_t kZip64EndSig = 0x06064b50, kZip64LocatorSig = 0x07064b50;
constexpr uint64_t kMaxDeflateRatio = 1032;  // deflate's largest expansion
constexpr uint64_t kChunk = uint64_t{1} << 30;  // zlib counts in unsigned int

[[noreturn]] void fail(const std::string& message) { throw IOError(printable_message(message)); }

template <class T>
T le(const std::string& s, size_t at) {
  return load_scalar<T>(s.data() + at, false);
}

// Reads n bytes at `offset`; the caller has checked the range against the size.
std::string read_at(std::ifstream& in, const std::string& path, uint64_t offset, uint64_t n) {
  std::string buf(static_cast<size_t>(n), '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(buf.data(), static_cast<std::streamsize>(n));
  if (static_cast<uint64_t>(in.gcount()) != n)
    fail_byte(path, static_cast<int64_t>(offset), fmt::format("cannot read {} bytes (read error)", n));
  return buf;
}

std::ifstream open_binary(const std::string& path, uint64_t& size) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(fmt::format("{}: is a directory, not an .npz file", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(fmt::format("{}: cannot open for reading (does it exist?)", path));
  in.seekg(0, std::ios::end);
  size = static_cast<uint64_t>(static_cast<std::streamoff>(in.tellg()));
  return in;
}

// ---- .npy -------------------------------------------------------------------

// The header dictionary: {'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }
struct NpyHeader {
  std::string descr;
  bool fortran = false;
  std::vector<int64_t> shape;
};

class HeaderParser {
 public:
  HeaderParser(std::string_view text, const std::string& what) : s_(text), what_(what) {}

  NpyHeader parse() {
    NpyHeader h;
    bool has_descr = false, has_order = false, has_shape = false;
    expect('{');
    while (true) {
      skip_ws();
      if (peek() == '}') break;
      const std::string key = string_literal();
      expect(':');
      skip_ws();
      if (key == "descr") {
        if (peek() == '[') bad("'descr' is a list: structured arrays (record dtypes) are not supported; save each field as an array of its own");
        h.descr = string_literal();
        has_descr = true;
      } else if (key == "fortran_order") {
        h.fortran = boolean();
        has_order = true;
      } else if (key == "shape") {
        h.shape = tuple();
        has_shape = true;
      } else {
        bad(fmt::format("unknown key '{}' in the header (expected 'descr', 'fortran_order', 'shape')", key));
      }
      skip_ws();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      skip_ws();
      if (peek() != '}') bad(fmt::format("expected ',' or '}}' at header character {}", pos_));
    }
    ++pos_;
    skip_ws();
    if (pos_ != s_.size()) bad(fmt::format("text after the header dictionary at header character {}", pos_));
    if (!has_descr || !has_order || !has_shape)
      bad("the header lacks one of 'descr', 'fortran_order', 'shape'");
    return h;
  }

 private:
  [[noreturn]] void bad(const std::string& why) const { fail(fmt::format("{}: bad .npy header: {}", what_, why)); }
  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
  void skip_ws() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
  }
  void expect(char c) {
    skip_ws();
    if (peek() != c) bad(fmt::format("expected '{}' at header character {}", c, pos_));
    ++pos_;
  }
  std::string string_literal() {
    skip_ws();
    const char q = peek();
    if (q != '\'' && q != '"') bad(fmt::format("expected a quoted string at header character {}", pos_));
    const size_t end = s_.find(q, pos_ + 1);
    if (end == std::string_view::npos) bad("unterminated string");
    std::string out(s_.substr(pos_ + 1, end - pos_ - 1));
    pos_ = end + 1;
    return out;
  }
  bool boolean() {
    if (s_.substr(pos_, 4) == "True") {
      pos_ += 4;
      return true;
    }
    if (s_.substr(pos_, 5) == "False") {
      pos_ += 5;
      return false;
    }
    bad("'fortran_order' is neither True nor False");
  }
  std::vector<int64_t> tuple() {
    expect('(');
    std::vector<int64_t> dims;
    while (true) {
      skip_ws();
      if (peek() == ')') break;
      if (peek() < '0' || peek() > '9') bad(fmt::format("expected a dimension at header character {}", pos_));
      int64_t d = 0;
      while (peek() >= '0' && peek() <= '9') {
        if (d > (std::numeric_limits<int64_t>::max() - 9) / 10) bad("a dimension is too large");
        d = d * 10 + (s_[pos_++] - '0');
      }
      if (peek() == 'L') ++pos_;  // Python 2's long literals
      dims.push_back(d);
      if (dims.size() > 32) bad("more than 32 dimensions");
      skip_ws();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() != ')') bad(fmt::format("expected ',' or ')' in 'shape' at header character {}", pos_));
    }
    ++pos_;
    return dims;
  }

  std::string_view s_;
  const std::string& what_;
  size_t pos_ = 0;
};

enum class Kind { Float, Signed, Unsigned, Bool };

struct DType {
  Kind kind;
  int bytes;
};

DType parse_dtype(const std::string& descr, const std::string& what) {
  const std::string supported = "supported: <f8 <f4 <i4 <i8 <u4 <u8 |u1 |b1";
  if (descr.find('O') != std::string::npos)
    fail(fmt::format("{}: holds Python objects (dtype '{}'), which cannot be read safely; convert it to a numeric "
                     "array first (SMPL's original pickles hold chumpy and scipy.sparse objects: save "
                     "np.array(x, dtype=np.float64) of each, and J_regressor densely with .toarray())",
                     what, descr));
  if (descr.size() != 3) fail(fmt::format("{}: unsupported dtype '{}' ({})", what, descr, supported));
  const char order = descr[0], n = descr[2];
  const std::string code = descr.substr(1);
  DType t{Kind::Float, n - '0'};
  if (code == "f8" || code == "f4") t.kind = Kind::Float;
  else if (code == "i4" || code == "i8") t.kind = Kind::Signed;
  else if (code == "u4" || code == "u8" || code == "u1") t.kind = Kind::Unsigned;
  else if (code == "b1") t.kind = Kind::Bool;
  else fail(fmt::format("{}: unsupported dtype '{}' ({})", what, descr, supported));
  if (order == '>' && t.bytes > 1)
    fail(fmt::format("{}: dtype '{}' is big-endian; only little-endian arrays are read (convert with "
                     "arr.astype('<{}'))",
                     what, descr, code));
  const bool ok = t.bytes == 1 ? (order == '|' || order == '<' || order == '>' || order == '=') : order == '<';
  if (!ok) fail(fmt::format("{}: unsupported byte order in dtype '{}' ({})", what, descr, supported));
  return t;
}

// C-order position of the element at Fortran-order position k.
std::vector<size_t> fortran_to_c(const std::vector<int64_t>& shape, size_t n) {
  std::vector<size_t> c_stride(shape.size(), 1);
  for (size_t d = shape.size(); d-- > 1;) c_stride[d - 1] = c_stride[d] * static_cast<size_t>(shape[d]);
  std::vector<size_t> map(n);
  for (size_t k = 0; k < n; ++k) {
    size_t rest = k, at = 0;
    for (size_t d = 0; d < shape.size(); ++d) {
      const auto dim = static_cast<size_t>(shape[d]);
      at += (rest % dim) * c_stride[d];
      rest /= dim;
    }
    map[k] = at;
  }
  return map;
}

}  // namespace

int64_t NpyArray::size() const {
  int64_t n = 1;
  for (int64_t d : shape) n *= d;
  return n;
}

std::string NpyArray::shape_text() const {
  std::string s = "(";
  for (size_t d = 0; d < shape.size(); ++d) s += (d ? ", " : "") + std::to_string(shape[d]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

NpyArray parse_npy(const std::string& bytes, const std::string& what) {
  static const std::string magic = "\x93NUMPY";
  if (bytes.size() < 10 || bytes.compare(0, 6, magic) != 0)
    fail(fmt::format("{}: not a .npy array (no \\x93NUMPY magic at its start)", what));
  const int major = static_cast<unsigned char>(bytes[6]), minor = static_cast<unsigned char>(bytes[7]);
  if ((major != 1 && major != 2 && major != 3) || minor != 0)
    fail(fmt::format("{}: .npy format version {}.{} is not supported (1.0, 2.0 and 3.0 are)", what, major, minor));
  const size_t len_bytes = major == 1 ? 2 : 4;
  if (bytes.size() < 8 + len_bytes) fail(fmt::format("{}: truncated .npy header", what));
  const uint64_t header_len = major == 1 ? le<uint16_t>(bytes, 8) : le<uint32_t>(bytes, 8);
  const uint64_t data_start = 8 + len_bytes + header_len;
  if (data_start > bytes.size())
    fail(fmt::format("{}: the .npy header claims {} bytes, the entry has only {} after the magic", what, header_len,
                     bytes.size() - 8 - len_bytes));
  const std::string_view text(bytes.data() + 8 + len_bytes, static_cast<size_t>(header_len));
  const NpyHeader h = HeaderParser(text, what).parse();
  const DType t = parse_dtype(h.descr, what);
  NpyArray a;
  a.dtype = h.descr;
  a.shape = h.shape;
  a.is_integer = t.kind != Kind::Float;
  // Exactly the bytes after the header, checked without overflow before
  // allocating anything.
  const uint64_t available = bytes.size() - data_start;
  uint64_t count = 1;
  bool zero = false;
  for (int64_t d : h.shape) zero = zero || d == 0;
  if (!zero) {
    for (int64_t d : h.shape) {
      if (static_cast<uint64_t>(d) > available / static_cast<uint64_t>(t.bytes) / count)
        fail(fmt::format("{}: shape {} of {}-byte elements needs more than the {} data bytes the entry has", what,
                         a.shape_text(), t.bytes, available));
      count *= static_cast<uint64_t>(d);
    }
  } else {
    count = 0;
  }
  if (count * static_cast<uint64_t>(t.bytes) != available)
    fail(fmt::format("{}: shape {} of {}-byte elements is {} bytes, the entry has {} data bytes", what,
                     a.shape_text(), t.bytes, count * static_cast<uint64_t>(t.bytes), available));
  const auto n = static_cast<size_t>(count);
  const char* p = bytes.data() + data_start;
  const std::vector<size_t> order = h.fortran && h.shape.size() > 1 ? fortran_to_c(h.shape, n) : std::vector<size_t>{};
  auto at = [&](size_t k) { return order.empty() ? k : order[k]; };
  if (t.kind == Kind::Float) {
    a.doubles.resize(n);
    for (size_t k = 0; k < n; ++k)
      a.doubles[at(k)] = t.bytes == 8 ? load_scalar<double>(p + 8 * k, false)
                                      : static_cast<double>(load_scalar<float>(p + 4 * k, false));
  } else {
    a.ints.resize(n);
    for (size_t k = 0; k < n; ++k) {
      int64_t v = 0;
      const char* q = p + static_cast<size_t>(t.bytes) * k;
      if (t.kind == Kind::Bool || t.bytes == 1) {
        v = static_cast<unsigned char>(*q);
        if (t.kind == Kind::Bool && v > 1) fail(fmt::format("{}: bool element {} is {}, not 0 or 1", what, k, v));
      } else if (t.kind == Kind::Signed) {
        v = t.bytes == 8 ? load_scalar<int64_t>(q, false) : load_scalar<int32_t>(q, false);
      } else if (t.bytes == 4) {
        v = load_scalar<uint32_t>(q, false);
      } else {
        const auto u = load_scalar<uint64_t>(q, false);
        if (u > static_cast<uint64_t>(std::numeric_limits<int64_t>::max()))
          fail(fmt::format("{}: uint64 element {} is {}, beyond the int64 range this reader keeps", what, k, u));
        v = static_cast<int64_t>(u);
      }
      a.ints[at(k)] = v;
    }
  }
  return a;
}

// ---- .zip -------------------------------------------------------------------

NpzReader::NpzReader(const std::string& path, const NpzReadOptions& options) : path_(path), options_(options) {
  std::ifstream in = open_binary(path, file_size_);
  if (file_size_ < 22)
    fail_byte(path, static_cast<int64_t>(file_size_),
              fmt::format("file too short ({} bytes) for a ZIP archive (.npz); truncated?", file_size_));
  // End of central directory: 22 bytes plus a comment of at most 65535.
  const uint64_t tail_len = std::min<uint64_t>(file_size_, 22 + 65535);
  const uint64_t tail_start = file_size_ - tail_len;
  const std::string tail = read_at(in, path, tail_start, tail_len);
  size_t eocd = std::string::npos;
  for (size_t i = tail.size() - 22 + 1; i-- > 0;) {
    if (le<uint32_t>(tail, i) == kEndSig) {
      eocd = i;
      break;
    }
  }
  if (eocd == std::string::npos)
    fail_byte(path, static_cast<int64_t>(file_size_),
              "no ZIP end-of-central-directory record: not an .npz file, or truncated");
  const uint64_t eocd_at = tail_start + eocd;
  uint64_t count = le<uint16_t>(tail, eocd + 10), cd_size = le<uint32_t>(tail, eocd + 12),
           cd_offset = le<uint32_t>(tail, eocd + 16);
  if (le<uint16_t>(tail, eocd + 4) != 0 || le<uint16_t>(tail, eocd + 6) != 0)
    fail_byte(path, static_cast<int64_t>(eocd_at), "multi-disk (split) ZIP archives are not supported");
  if (count == 0xFFFF || cd_size == 0xFFFFFFFF || cd_offset == 0xFFFFFFFF) {
    // ZIP64: the locator sits just before the end record.
    if (eocd_at < 20 || le<uint32_t>(read_at(in, path, eocd_at - 20, 4), 0) != kZip64LocatorSig)
      fail_byte(path, static_cast<int64_t>(eocd_at), "ZIP64 sizes are announced but there is no ZIP64 locator");
    const std::string loc = read_at(in, path, eocd_at - 20, 20);
    const uint64_t rec_at = le<uint64_t>(loc, 8);
    if (rec_at > eocd_at - 20 || eocd_at - 20 - rec_at < 56)
      fail_byte(path, static_cast<int64_t>(eocd_at - 20), "the ZIP64 locator points outside the file");
    const std::string rec = read_at(in, path, rec_at, 56);
    if (le<uint32_t>(rec, 0) != kZip64EndSig)
      fail_byte(path, static_cast<int64_t>(rec_at), "no ZIP64 end-of-central-directory record where the locator points");
    count = le<uint64_t>(rec, 32);
    cd_size = le<uint64_t>(rec, 40);
    cd_offset = le<uint64_t>(rec, 48);
  }
  if (cd_offset > file_size_ || cd_size > file_size_ - cd_offset)
    fail_byte(path, static_cast<int64_t>(eocd_at),
              fmt::format("the central directory ({} bytes at byte {}) reaches past the end of the file ({} bytes); "
                          "truncated?",
                          cd_size, cd_offset, file_size_));
  if (count > cd_size / 46)
    fail_byte(path, static_cast<int64_t>(eocd_at),
              fmt::format("{} entries cannot fit a central directory of {} bytes", count, cd_size));
  const std::string cd = read_at(in, path, cd_offset, cd_size);
  size_t pos = 0;
  for (uint64_t e = 0; e < count; ++e) {
    const auto at = static_cast<int64_t>(cd_offset + pos);
    if (cd.size() - pos < 46 || le<uint32_t>(cd, pos) != kCentralSig)
      fail_byte(path, at, fmt::format("central directory entry {} is missing or corrupt", e));
    const uint16_t flags = le<uint16_t>(cd, pos + 8);
    Entry en;
    en.method = le<uint16_t>(cd, pos + 10);
    en.crc = le<uint32_t>(cd, pos + 16);
    en.compressed = le<uint32_t>(cd, pos + 20);
    en.uncompressed = le<uint32_t>(cd, pos + 24);
    const size_t name_len = le<uint16_t>(cd, pos + 28), extra_len = le<uint16_t>(cd, pos + 30),
                 comment_len = le<uint16_t>(cd, pos + 32);
    en.local_offset = le<uint32_t>(cd, pos + 42);
    if (cd.size() - pos - 46 < name_len + extra_len + comment_len)
      fail_byte(path, at, fmt::format("central directory entry {} reaches past the directory's end", e));
    std::string name = cd.substr(pos + 46, name_len);
    // ZIP64 extra field: the 64-bit values of the fields set to 0xFFFFFFFF, in order.
    size_t x = pos + 46 + name_len;
    const size_t x_end = x + extra_len;
    while (x + 4 <= x_end) {
      const uint16_t id = le<uint16_t>(cd, x), len = le<uint16_t>(cd, x + 2);
      if (x + 4 + len > x_end) break;
      if (id == 0x0001) {
        size_t f = x + 4;
        const size_t f_end = f + len;
        for (uint64_t* field : {&en.uncompressed, &en.compressed, &en.local_offset}) {
          if (*field != 0xFFFFFFFF) continue;
          if (f + 8 > f_end) fail_byte(path, at, fmt::format("entry '{}': ZIP64 extra field too short", name));
          *field = le<uint64_t>(cd, f);
          f += 8;
        }
      }
      x += 4 + len;
    }
    pos += 46 + name_len + extra_len + comment_len;
    const std::string who = fmt::format("{}: entry '{}'", path, name);
    if (flags & 0x1) fail(who + ": is encrypted; encrypted .npz entries are not supported");
    if (en.method != 0 && en.method != 8)
      fail(fmt::format("{}: compression method {} is not supported (stored 0 and deflated 8 are; numpy writes "
                       "these)",
                       who, en.method));
    if (name.size() < 5 || name.compare(name.size() - 4, 4, ".npy") != 0)
      fail(who + ": is not a .npy array (an .npz holds only NAME.npy entries)");
    en.name = name.substr(0, name.size() - 4);
    if (en.local_offset > file_size_ || en.compressed > file_size_ - en.local_offset)
      fail(fmt::format("{}: {} bytes at byte {} reach past the end of the file ({} bytes); truncated?", who,
                       en.compressed, en.local_offset, file_size_));
    if (en.uncompressed > options_.max_entry_bytes)
      fail(fmt::format("{}: {} bytes uncompressed, more than the limit of {} bytes", who, en.uncompressed,
                       options_.max_entry_bytes));
    if (en.method == 0 ? en.uncompressed != en.compressed
                       : en.uncompressed > en.compressed * kMaxDeflateRatio + 1024)
      fail(fmt::format("{}: declares {} bytes uncompressed from {} stored bytes, which the {} method cannot give",
                       who, en.uncompressed, en.compressed, en.method == 0 ? "stored" : "deflate"));
    if (std::find(names_.begin(), names_.end(), en.name) != names_.end())
      fail(who + ": appears twice in the archive");
    names_.push_back(en.name);
    entries_.push_back(std::move(en));
  }
}

bool NpzReader::contains(const std::string& name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

NpyArray NpzReader::read(const std::string& name) const {
  const auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  const std::string who = fmt::format("{}: entry '{}.npy'", path_, name);
  if (it == entries_.end()) {
    std::string all;
    for (const auto& n : names_) all += (all.empty() ? "" : ", ") + n;
    fail(fmt::format("{}: no such array in the file (it has: {})", who, all.empty() ? "none" : all));
  }
  const Entry& e = *it;
  uint64_t size = 0;
  std::ifstream in = open_binary(path_, size);
  if (size != file_size_) fail(who + ": the file changed size while being read");
  if (e.local_offset > size - std::min<uint64_t>(size, 30))
    fail(fmt::format("{}: its local header at byte {} is past the end of the file", who, e.local_offset));
  const std::string local = read_at(in, path_, e.local_offset, 30);
  if (le<uint32_t>(local, 0) != kLocalSig)
    fail(fmt::format("{}: no local file header at byte {} (corrupt archive)", who, e.local_offset));
  const uint64_t data_at = e.local_offset + 30 + le<uint16_t>(local, 26) + le<uint16_t>(local, 28);
  if (data_at > size || e.compressed > size - data_at)
    fail(fmt::format("{}: its {} bytes of data at byte {} reach past the end of the file ({} bytes); truncated?",
                     who, e.compressed, data_at, size));
  const std::string raw = read_at(in, path_, data_at, e.compressed);
  std::string bytes;
  if (e.method == 0) {
    bytes = raw;
  } else {
    bytes.assign(static_cast<size_t>(e.uncompressed), '\0');
    z_stream z{};
    if (inflateInit2(&z, -MAX_WBITS) != Z_OK) fail(who + ": cannot initialise zlib");
    uint64_t in_done = 0, out_done = 0;
    int rc = Z_OK;
    while (rc == Z_OK) {
      z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data() + in_done));
      z.avail_in = static_cast<uInt>(std::min(kChunk, raw.size() - in_done));
      z.next_out = reinterpret_cast<Bytef*>(bytes.data() + out_done);
      z.avail_out = static_cast<uInt>(std::min(kChunk, bytes.size() - out_done));
      const uInt in_before = z.avail_in, out_before = z.avail_out;
      rc = inflate(&z, Z_NO_FLUSH);
      in_done += in_before - z.avail_in;
      out_done += out_before - z.avail_out;
      if (rc == Z_BUF_ERROR && out_done == bytes.size()) break;   // more output than declared
      if (rc == Z_BUF_ERROR && in_done == raw.size()) break;      // input ended early
      if (rc == Z_BUF_ERROR) rc = Z_OK;
    }
    const std::string zlib_message = rc == Z_DATA_ERROR && z.msg ? z.msg : "";
    inflateEnd(&z);
    if (rc != Z_STREAM_END)
      fail(fmt::format("{}: corrupt deflate data ({}; {} of {} bytes inflated)", who,
                       !zlib_message.empty() ? zlib_message
                       : out_done == bytes.size() ? "it inflates to more than the declared size"
                                                  : "the compressed data ends early",
                       out_done, e.uncompressed));
    if (out_done != e.uncompressed)
      fail(fmt::format("{}: inflates to {} bytes, the archive declares {}", who, out_done, e.uncompressed));
  }
  uLong crc = crc32(0L, Z_NULL, 0);
  for (uint64_t off = 0; off < bytes.size(); off += kChunk)
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + off),
                static_cast<uInt>(std::min<uint64_t>(kChunk, bytes.size() - off)));
  if (crc != e.crc) fail(fmt::format("{}: CRC-32 mismatch (file {:08x}, data {:08x}): corrupt archive", who, e.crc, crc));
  return parse_npy(bytes, who);
}

std::map<std::string, NpyArray> read_npz(const std::string& path, const NpzReadOptions& options) {
  const NpzReader reader(path, options);
  std::map<std::string, NpyArray> out;
  for (const auto& n : reader.names()) out.emplace(n, reader.read(n));
  return out;
}

}  // namespace knitforge
