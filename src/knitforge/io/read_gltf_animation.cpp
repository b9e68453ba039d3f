#include "knitforge/io/read_gltf_animation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "knitforge/io/io_detail.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using io_detail::printable_message;

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;
/// At most this many values (components) are read from accessors in all:
/// 8 bytes each as read, about twice that held.
constexpr uint64_t kMaxValues = uint64_t{1} << 26;

uint32_t u32_at(const std::string& s, size_t at) { return io_detail::load_scalar<uint32_t>(s.data() + at, false); }

int component_bytes(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte: return 1;
    case kShort:
    case kUnsignedShort: return 2;
    case kUnsignedInt:
    case kFloat: return 4;
    default: return 0;
  }
}

int type_components(const std::string& t) {
  if (t == "SCALAR") return 1;
  if (t == "VEC2") return 2;
  if (t == "VEC3") return 3;
  if (t == "VEC4") return 4;
  if (t == "MAT4") return 16;
  return 0;  // the other matrices are not used here
}

std::string base64_decode(std::string_view s, bool& ok) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+' || c == '-') return 62;
    if (c == '/' || c == '_') return 63;
    return -1;
  };
  std::string out;
  out.reserve(s.size() / 4 * 3);
  uint32_t acc = 0;
  int bits = 0;
  ok = true;
  size_t i = 0;
  for (; i < s.size() && s[i] != '='; ++i) {
    const int v = value(s[i]);
    if (v < 0) {
      ok = false;
      return {};
    }
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((acc >> bits) & 0xFF));
    }
  }
  for (; i < s.size(); ++i) {
    if (s[i] != '=') ok = false;
  }
  return out;
}

std::string percent_decode(const std::string& s, bool& ok) {
  std::string out;
  ok = true;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out.push_back(s[i]);
      continue;
    }
    auto hex = [](char c) {
      if (c >= '0' && c <= '9') return c - '0';
      if (c >= 'a' && c <= 'f') return c - 'a' + 10;
      if (c >= 'A' && c <= 'F') return c - 'A' + 10;
      return -1;
    };
    if (i + 2 >= s.size() || hex(s[i + 1]) < 0 || hex(s[i + 2]) < 0) {
      ok = false;
      return {};
    }
    out.push_back(static_cast<char>(hex(s[i + 1]) * 16 + hex(s[i + 2])));
    i += 2;
  }
  return out;
}

struct View {
  size_t buffer = 0;
  uint64_t offset = 0, length = 0, stride = 0;
};

/// The values of one accessor, as numbers (not yet normalised).
struct Values {
  int component_type = 0;
  int components = 0;
  uint64_t count = 0;
  bool normalized = false;
  std::vector<double> v;
};

class Doc {
 public:
  Doc(std::string path, const json& j) : path_(std::move(path)), j_(j) {}

  [[noreturn]] void fail(const std::string& element, const std::string& what) const {
    throw IOError(printable_message(fmt::format("{}: {}: {}", path_, element, what)));
  }

  /// The array `key` of the root ([] when absent).
  const json& root_array(const char* key) const {
    static const json empty = json::array();
    if (!j_.contains(key)) return empty;
    const json& a = j_[key];
    if (!a.is_array()) fail(key, "must be an array");
    return a;
  }
  /// Element `index` of root array `key`, which must be an object.
  const json& item(const char* key, uint64_t index, const std::string& from) const {
    const json& a = root_array(key);
    if (index >= a.size()) {
      fail(from, fmt::format("refers to {}[{}], but the file has {} {}", key, index, a.size(), key));
    }
    const json& o = a[index];
    if (!o.is_object()) fail(fmt::format("{}[{}]", key, index), "must be an object");
    return o;
  }
  uint64_t uint(const json& o, const char* key, const std::string& element,
                std::optional<uint64_t> fallback = std::nullopt) const {
    if (!o.contains(key)) {
      if (!fallback) fail(element, fmt::format("has no \"{}\"", key));
      return *fallback;
    }
    const json& v = o[key];
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
      fail(element, fmt::format("\"{}\" must be a non-negative integer (got {})", key, v.dump()));
    return v.get<uint64_t>();
  }
  std::string string(const json& o, const char* key, const std::string& element, const std::string& fallback) const {
    if (!o.contains(key)) return fallback;
    if (!o[key].is_string()) fail(element, fmt::format("\"{}\" must be a string", key));
    return o[key].get<std::string>();
  }
  std::vector<double> numbers(const json& o, const char* key, const std::string& element, size_t n) const {
    const json& a = o[key];
    if (!a.is_array() || (n > 0 && a.size() != n))
      fail(element, n > 0 ? fmt::format("\"{}\" must be an array of {} numbers", key, n)
                          : fmt::format("\"{}\" must be an array of numbers", key));
    std::vector<double> out;
    for (const json& x : a) {
      if (!x.is_number() || !std::isfinite(x.get<double>()))
        fail(element, fmt::format("\"{}\" must hold finite numbers", key));
      out.push_back(x.get<double>());
    }
    return out;
  }

  const std::string& path() const { return path_; }
  const json& j() const { return j_; }

  std::vector<std::string> buffers;  // the bytes of each buffer (at least its byteLength)
  uint64_t values_read = 0;

  View view(uint64_t index, const std::string& from) const {
    const json& o = item("bufferViews", index, from);
    const std::string el = fmt::format("bufferViews[{}]", index);
    View v;
    v.buffer = static_cast<size_t>(uint(o, "buffer", el));
    if (v.buffer >= buffers.size())
      fail(el, fmt::format("refers to buffers[{}], but the file has {} buffers", v.buffer, buffers.size()));
    v.offset = uint(o, "byteOffset", el, 0);
    v.length = uint(o, "byteLength", el);
    v.stride = uint(o, "byteStride", el, 0);
    if (v.length == 0) fail(el, "byteLength must be at least 1");
    if (o.contains("byteStride") && (v.stride < 4 || v.stride > 252 || v.stride % 4 != 0))
      fail(el, fmt::format("byteStride {} must be a multiple of 4 in [4, 252]", v.stride));
    const uint64_t size = buffers[v.buffer].size();
    if (v.offset > size || v.length > size - v.offset)
      fail(el, fmt::format("bytes [{}, +{}) lie outside buffers[{}] ({} bytes)", v.offset, v.length, v.buffer, size));
    return v;
  }

  /// Reads `count` elements of `components` components of `type` from a
  /// view at `offset` (stride 0 = tightly packed) into out (appending).
  void read_elements(const View& v, uint64_t offset, uint64_t stride, uint64_t count, int components, int type,
                     const std::string& el, std::vector<double>& out) const {
    const uint64_t elem = static_cast<uint64_t>(component_bytes(type)) * static_cast<uint64_t>(components);
    if (stride == 0) stride = elem;
    if (stride < elem) fail(el, fmt::format("byteStride {} is less than an element ({} bytes)", stride, elem));
    // count <= kMaxValues and stride <= 252: no overflow.
    if (offset > v.length || (count > 0 && (v.length - offset < elem || (count - 1) * stride > v.length - offset - elem)))
      fail(el, fmt::format("{} elements of {} bytes from byte {} (stride {}) do not fit in its bufferView ({} bytes)",
                           count, elem, offset, stride, v.length));
    const char* base = buffers[v.buffer].data() + v.offset + offset;
    const size_t cb = static_cast<size_t>(component_bytes(type));
    for (uint64_t i = 0; i < count; ++i) {
      const char* p = base + i * stride;
      for (int c = 0; c < components; ++c, p += cb) {
        switch (type) {
          case kByte: out.push_back(static_cast<int8_t>(*p)); break;
          case kUnsignedByte: out.push_back(static_cast<uint8_t>(*p)); break;
          case kShort: out.push_back(io_detail::load_scalar<int16_t>(p, false)); break;
          case kUnsignedShort: out.push_back(io_detail::load_scalar<uint16_t>(p, false)); break;
          case kUnsignedInt: out.push_back(io_detail::load_scalar<uint32_t>(p, false)); break;
          default: out.push_back(io_detail::load_scalar<float>(p, false)); break;
        }
      }
    }
  }

  /// Accessor `index`, used as `use` ("POSITION of meshes[0].primitives[1]"):
  /// its type must be one of `types`, its component type one of `component_types`.
  Values accessor(uint64_t index, const std::string& use, std::initializer_list<const char*> types,
                  std::initializer_list<int> component_types) {
    const json& o = item("accessors", index, use);
    const std::string el = fmt::format("accessors[{}] ({})", index, use);
    Values r;
    r.component_type = static_cast<int>(std::min<uint64_t>(uint(o, "componentType", el), 1 << 20));
    const std::string type = string(o, "type", el, "");
    bool type_ok = false, ct_ok = false;
    std::string type_list, ct_list;
    for (const char* t : types) {
      type_ok = type_ok || type == t;
      type_list += (type_list.empty() ? "" : " or ") + std::string(t);
    }
    for (int c : component_types) {
      ct_ok = ct_ok || r.component_type == c;
      ct_list += (ct_list.empty() ? "" : ", ") + std::to_string(c);
    }
    if (!type_ok) fail(el, fmt::format("type is '{}', it must be {}", type, type_list));
    if (!ct_ok) {
      fail(el, fmt::format("componentType is {}, it must be one of {} (5120 byte, 5121 unsigned byte, 5122 short, "
                           "5123 unsigned short, 5125 unsigned int, 5126 float)",
                           r.component_type, ct_list));
    }
    r.components = type_components(type);
    r.count = uint(o, "count", el);
    if (r.count == 0) fail(el, "count must be at least 1");
    if (o.contains("normalized")) {
      if (!o["normalized"].is_boolean()) fail(el, "\"normalized\" must be true or false");
      r.normalized = o["normalized"].get<bool>();
    }
    const uint64_t n = r.count * static_cast<uint64_t>(r.components);
    if (r.count > kMaxValues || n > kMaxValues - std::min(kMaxValues, values_read)) {
      fail(el, fmt::format("count {}: the file holds more than the {} values read at most; use a coarser mesh or "
                           "fewer frames",
                           r.count, kMaxValues));
    }
    values_read += n;
    if (o.contains("bufferView")) {
      const View v = view(uint(o, "bufferView", el), el);
      r.v.reserve(static_cast<size_t>(n));
      read_elements(v, uint(o, "byteOffset", el, 0), v.stride, r.count, r.components, r.component_type, el, r.v);
    } else {
      r.v.assign(static_cast<size_t>(n), 0.0);  // zeros (then sparse values, if any)
    }
    if (o.contains("sparse")) {
      const json& s = o["sparse"];
      const std::string sel = el + ".sparse";
      if (!s.is_object() || !s.contains("indices") || !s.contains("values") || !s["indices"].is_object() ||
          !s["values"].is_object())
        fail(sel, "must be an object with \"count\", \"indices\" and \"values\"");
      const uint64_t sc = uint(s, "count", sel);
      if (sc == 0 || sc > r.count) fail(sel, fmt::format("count {} must be in [1, {}]", sc, r.count));
      const json& si = s["indices"];
      const int ict = static_cast<int>(std::min<uint64_t>(uint(si, "componentType", sel + ".indices"), 1 << 20));
      if (ict != kUnsignedByte && ict != kUnsignedShort && ict != kUnsignedInt)
        fail(sel + ".indices", fmt::format("componentType {} must be 5121, 5123 or 5125", ict));
      std::vector<double> idx, val;
      read_elements(view(uint(si, "bufferView", sel + ".indices"), sel + ".indices"), uint(si, "byteOffset", sel, 0),
                    0, sc, 1, ict, sel + ".indices", idx);
      const json& sv = s["values"];
      read_elements(view(uint(sv, "bufferView", sel + ".values"), sel + ".values"), uint(sv, "byteOffset", sel, 0), 0,
                    sc, r.components, r.component_type, sel + ".values", val);
      for (uint64_t k = 0; k < sc; ++k) {
        if (idx[k] >= static_cast<double>(r.count) || (k > 0 && !(idx[k] > idx[k - 1])))
          fail(sel + ".indices", fmt::format("index {} ({}) is out of range [0, {}) or not increasing", k,
                                             static_cast<uint64_t>(idx[k]), r.count));
        const auto at = static_cast<size_t>(idx[k]) * static_cast<size_t>(r.components);
        for (int c = 0; c < r.components; ++c) r.v[at + static_cast<size_t>(c)] = val[k * r.components + c];
      }
    }
    for (double x : r.v) {
      if (!std::isfinite(x)) fail(el, "holds a value that is not finite (NaN or infinity)");
    }
    return r;
  }

  /// Float data (float32, or normalised integers when `normalized_ok`), normalised.
  Values floats(uint64_t index, const std::string& use, std::initializer_list<const char*> types,
                bool normalized_ok) {
    Values r = normalized_ok ? accessor(index, use, types, {kFloat, kByte, kUnsignedByte, kShort, kUnsignedShort})
                             : accessor(index, use, types, {kFloat});
    if (r.component_type != kFloat) {
      if (!r.normalized)
        fail(fmt::format("accessors[{}] ({})", index, use), "integer values must be \"normalized\": true");
      const double scale = r.component_type == kByte            ? 127.0
                           : r.component_type == kUnsignedByte   ? 255.0
                           : r.component_type == kShort          ? 32767.0
                                                                 : 65535.0;
      for (double& x : r.v) x = std::max(x / scale, -1.0);
    }
    return r;
  }

 private:
  std::string path_;
  const json& j_;
};

std::string load_external(const Doc& d, const std::string& el, const std::string& uri, uint64_t length) {
  bool ok = true;
  const std::string decoded = percent_decode(uri, ok);
  if (!ok) d.fail(el, fmt::format("uri '{}' has a bad %-escape", uri));
  const size_t colon = decoded.find(':'), slash = decoded.find('/');
  if ((colon != std::string::npos && (slash == std::string::npos || colon < slash)) ||
      fs::path(decoded).is_absolute()) {
    d.fail(el, fmt::format("uri '{}' is not a relative file name or a data: URI; put the buffer next to the file "
                           "or export a .glb",
                           uri));
  }
  const fs::path file = fs::path(d.path()).parent_path() / decoded;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) d.fail(el, fmt::format("buffer file '{}' does not exist", file.string()));
  const uintmax_t size = fs::file_size(file, ec);
  if (ec || size < length)
    d.fail(el, fmt::format("buffer file '{}' has {} bytes, byteLength says {}", file.string(), ec ? 0 : size, length));
  std::ifstream in(file, std::ios::binary);
  std::string out(static_cast<size_t>(length), '\0');
  if (!in.read(out.data(), static_cast<std::streamsize>(length)))
    d.fail(el, fmt::format("buffer file '{}' cannot be read", file.string()));
  return out;
}

void load_buffers(Doc& d, const std::string* bin) {
  const json& bs = d.root_array("buffers");
  for (size_t i = 0; i < bs.size(); ++i) {
    const std::string el = fmt::format("buffers[{}]", i);
    if (!bs[i].is_object()) d.fail(el, "must be an object");
    const uint64_t length = d.uint(bs[i], "byteLength", el);
    if (length == 0) d.fail(el, "byteLength must be at least 1");
    if (!bs[i].contains("uri")) {
      if (i != 0 || !bin) d.fail(el, "has no \"uri\" and is not the BIN chunk of a .glb (only buffers[0] can be)");
      if (bin->size() < length)
        d.fail(el, fmt::format("byteLength {} is more than the BIN chunk's {} bytes", length, bin->size()));
      d.buffers.push_back(*bin);
      continue;
    }
    const std::string uri = d.string(bs[i], "uri", el, "");
    if (uri.rfind("data:", 0) == 0) {
      const size_t at = uri.find(";base64,");
      if (at == std::string::npos) d.fail(el, "a data: URI must be base64 (\";base64,\")");
      bool ok = true;
      std::string bytes = base64_decode(std::string_view(uri).substr(at + 8), ok);
      if (!ok) d.fail(el, "the data: URI is not valid base64");
      if (bytes.size() < length)
        d.fail(el, fmt::format("the data: URI holds {} bytes, byteLength says {}", bytes.size(), length));
      d.buffers.push_back(std::move(bytes));
    } else {
      d.buffers.push_back(load_external(d, el, uri, length));
    }
  }
}

/// The JSON and the BIN chunk of a .glb, or the JSON of a .gltf.
json parse_file(const std::string& path, const std::string& data, std::string& bin, bool& has_bin) {
  has_bin = false;
  std::string_view text = data;
  auto bad = [&](size_t at, const std::string& what) -> void { io_detail::fail_byte(path, static_cast<int64_t>(at), what); };
  if (data.size() >= 4 && u32_at(data, 0) == kMagic) {
    if (data.size() < 20) bad(0, "a .glb needs a 12-byte header and a JSON chunk; the file is cut short");
    const uint32_t version = u32_at(data, 4), length = u32_at(data, 8);
    if (version != 2) bad(4, fmt::format("GLB version {}; only glTF 2.0 is read (re-export as glTF 2.0)", version));
    if (length > data.size() || length < 20)
      bad(8, fmt::format("the header says {} bytes, the file has {} (cut short?)", length, data.size()));
    const uint32_t json_length = u32_at(data, 12), json_type = u32_at(data, 16);
    if (json_type != kChunkJson) bad(16, "the first chunk must be the JSON chunk");
    if (json_length > length - 20) bad(12, fmt::format("the JSON chunk ({} bytes) runs past the file's end", json_length));
    text = std::string_view(data).substr(20, json_length);
    const uint64_t next = 20 + static_cast<uint64_t>(json_length);
    if (next + 8 <= length) {
      const uint32_t bin_length = u32_at(data, next), bin_type = u32_at(data, next + 4);
      if (bin_type == kChunkBin) {
        if (bin_length > length - next - 8)
          bad(next, fmt::format("the BIN chunk ({} bytes) runs past the file's end", bin_length));
        bin = data.substr(next + 8, bin_length);
        has_bin = true;
      }
    }
  }
  json j = json::parse(text, nullptr, false);
  if (j.is_discarded()) {
    throw IOError(fmt::format("{}: not a glTF file: {} (a .glb or a .gltf JSON file)", path,
                              text.data() == data.data() ? "not JSON and no GLB header" : "the JSON chunk is not JSON"));
  }
  if (!j.is_object()) throw IOError(fmt::format("{}: the glTF JSON must be an object", path));
  return j;
}

/// skins[index] of the file: its joints' nodes and inverse bind matrices.
GltfAnimatedMesh::Skin read_skin(Doc& d, uint64_t index, size_t num_nodes, const std::string& from) {
  const json& o = d.item("skins", index, from);
  const std::string el = fmt::format("skins[{}]", index);
  GltfAnimatedMesh::Skin skin;
  if (!o.contains("joints") || !o["joints"].is_array() || o["joints"].empty())
    d.fail(el, "must have a non-empty \"joints\" array of node indices");
  std::set<uint64_t> seen;
  for (const json& x : o["joints"]) {
    if (!x.is_number_unsigned() || x.get<uint64_t>() >= num_nodes)
      d.fail(el, fmt::format("joint {} is not a node index (the file has {} nodes)", x.dump(), num_nodes));
    if (!seen.insert(x.get<uint64_t>()).second) d.fail(el, fmt::format("joint {} is listed twice", x.dump()));
    skin.joints.push_back(x.get<int>());
  }
  const size_t nj = skin.joints.size();
  std::array<double, 16> identity{};
  for (int k = 0; k < 4; ++k) identity[static_cast<size_t>(5 * k)] = 1.0;
  skin.inverse_bind.assign(nj, identity);
  if (o.contains("inverseBindMatrices")) {
    const Values m = d.floats(d.uint(o, "inverseBindMatrices", el), "inverseBindMatrices of " + el, {"MAT4"}, false);
    if (m.count < nj)
      d.fail(el, fmt::format("inverseBindMatrices holds {} matrices for {} joints", m.count, nj));
    for (size_t j = 0; j < nj; ++j) {
      std::copy_n(m.v.begin() + static_cast<std::ptrdiff_t>(16 * j), 16, skin.inverse_bind[j].begin());
      const auto& b = skin.inverse_bind[j];  // column-major: the last row is b[3], b[7], b[11], b[15]
      if (std::abs(b[3]) > 1e-6 || std::abs(b[7]) > 1e-6 || std::abs(b[11]) > 1e-6 || std::abs(b[15] - 1) > 1e-6)
        d.fail(el, fmt::format("inverse bind matrix {} does not end in the row (0, 0, 0, 1)", j));
    }
  }
  return skin;
}

/// The joints and weights of each vertex of a skinned primitive (JOINTS_n /
/// WEIGHTS_n), sorted by joint, weights rescaled to sum to 1.
std::vector<std::vector<std::pair<int, double>>> read_influences(Doc& d, const json& attrs, const std::string& pel,
                                                                 size_t num_vertices, size_t num_joints) {
  std::vector<std::vector<std::pair<int, double>>> infl(num_vertices);
  int sets = 0;
  for (;; ++sets) {
    const std::string jn = fmt::format("JOINTS_{}", sets), wn = fmt::format("WEIGHTS_{}", sets);
    if (!attrs.contains(jn) && !attrs.contains(wn)) break;
    if (!attrs.contains(jn) || !attrs.contains(wn))
      d.fail(pel, fmt::format("has {} without {}", attrs.contains(jn) ? jn : wn, attrs.contains(jn) ? wn : jn));
    const Values joints =
        d.accessor(d.uint(attrs, jn.c_str(), pel), jn + " of " + pel, {"VEC4"}, {kUnsignedByte, kUnsignedShort});
    const Values weights = d.floats(d.uint(attrs, wn.c_str(), pel), wn + " of " + pel, {"VEC4"}, true);
    if (weights.component_type == kByte || weights.component_type == kShort)
      d.fail(pel, fmt::format("{} must be float or normalised unsigned byte/short", wn));
    if (joints.count != num_vertices || weights.count != num_vertices)
      d.fail(pel, fmt::format("{} has {} and {} {} entries for {} vertices", jn, joints.count, wn, weights.count,
                              num_vertices));
    for (size_t v = 0; v < num_vertices; ++v) {
      for (size_t c = 0; c < 4; ++c) {
        const double w = weights.v[4 * v + c], j = joints.v[4 * v + c];
        if (w < 0) d.fail(pel, fmt::format("{}: vertex {} has a negative weight ({})", wn, v, w));
        if (w == 0) continue;
        if (j >= static_cast<double>(num_joints))
          d.fail(pel, fmt::format("{}: vertex {} uses joint {}, but the skin has {} joints", jn, v, j, num_joints));
        infl[v].emplace_back(static_cast<int>(j), w);
      }
    }
  }
  if (sets == 0) d.fail(pel, "belongs to a skinned node but has no JOINTS_0 / WEIGHTS_0");
  for (size_t v = 0; v < num_vertices; ++v) {
    auto& f = infl[v];
    std::sort(f.begin(), f.end());
    // The same joint in two sets: one entry.
    size_t out = 0;
    for (size_t k = 0; k < f.size(); ++k) {
      if (out > 0 && f[out - 1].first == f[k].first) f[out - 1].second += f[k].second;
      else f[out++] = f[k];
    }
    f.resize(out);
    double sum = 0;
    for (const auto& [j, w] : f) sum += w;
    if (!(std::abs(sum - 1.0) <= 0.02))
      d.fail(pel, fmt::format("the skin weights of vertex {} sum to {:.4g}, not 1 (re-export with normalised weights)",
                              v, sum));
    for (auto& jw : f) jw.second /= sum;
  }
  return infl;
}

}  // namespace

GltfAnimatedMesh read_gltf_animation(const std::string& path, const GltfReadOptions& options) {
  const std::string data = io_detail::load_file(path);
  std::string bin;
  bool has_bin = false;
  const json j = parse_file(path, data, bin, has_bin);
  Doc d(path, j);
  if (!j.contains("asset") || !j["asset"].is_object())
    d.fail("asset", "is missing (every glTF file has \"asset\": {\"version\": \"2.0\"})");
  const std::string version = d.string(j["asset"], "version", "asset", "");
  if (version.rfind("2.", 0) != 0)
    d.fail("asset.version", fmt::format("is '{}'; only glTF 2.x is read (re-export as glTF 2.0)", version));
  if (j.contains("extensionsRequired")) {
    const json& e = j["extensionsRequired"];
    if (!e.is_array()) d.fail("extensionsRequired", "must be an array");
    if (!e.empty()) {
      d.fail("extensionsRequired", fmt::format("{}: no extension is read; export without compression or "
                                               "quantization (plain float32 positions)",
                                               e.dump()));
    }
  }
  load_buffers(d, has_bin ? &bin : nullptr);

  GltfAnimatedMesh out;
  out.path = path;

  // Nodes and the hierarchy.
  const json& jnodes = d.root_array("nodes");
  const size_t nn = jnodes.size();
  out.nodes.resize(nn);
  std::vector<int64_t> node_mesh(nn, -1);
  for (size_t i = 0; i < nn; ++i) {
    const json& o = d.item("nodes", i, "nodes");
    const std::string el = fmt::format("nodes[{}]", i);
    GltfAnimatedMesh::Node& n = out.nodes[i];
    if (o.contains("matrix")) {
      const std::vector<double> m = d.numbers(o, "matrix", el, 16);
      std::copy(m.begin(), m.end(), n.matrix.begin());
      n.has_matrix = true;
      if (o.contains("translation") || o.contains("rotation") || o.contains("scale"))
        d.fail(el, "has both \"matrix\" and translation/rotation/scale");
    }
    if (o.contains("translation")) {
      const auto t = d.numbers(o, "translation", el, 3);
      n.translation = Vec3(t[0], t[1], t[2]);
    }
    if (o.contains("rotation")) {
      const auto r = d.numbers(o, "rotation", el, 4);
      if (!(std::hypot(r[0], r[1], r[2]) + std::abs(r[3]) > 0)) d.fail(el, "rotation must be a unit quaternion");
      std::copy(r.begin(), r.end(), n.rotation.begin());
    }
    if (o.contains("scale")) {
      const auto s = d.numbers(o, "scale", el, 3);
      n.scale = Vec3(s[0], s[1], s[2]);
    }
    if (o.contains("weights")) n.weights = d.numbers(o, "weights", el, 0);
    if (o.contains("mesh")) {
      node_mesh[i] = static_cast<int64_t>(d.uint(o, "mesh", el));
      (void)d.item("meshes", static_cast<uint64_t>(node_mesh[i]), el);
    }
    if (o.contains("children")) {
      const json& c = o["children"];
      if (!c.is_array()) d.fail(el, "\"children\" must be an array of node indices");
      for (const json& x : c) {
        if (!x.is_number_unsigned() || x.get<uint64_t>() >= nn)
          d.fail(el, fmt::format("child {} is not a node index (the file has {} nodes)", x.dump(), nn));
        const size_t ch = x.get<size_t>();
        if (ch == i || out.nodes[ch].parent >= 0)
          d.fail(el, fmt::format("child {} is the node itself or already has a parent", ch));
        out.nodes[ch].parent = static_cast<int>(i);
      }
    }
  }
  for (size_t i = 0; i < nn; ++i) {  // no cycles
    size_t steps = 0;
    for (int p = out.nodes[i].parent; p >= 0; p = out.nodes[static_cast<size_t>(p)].parent) {
      if (++steps > nn) d.fail(fmt::format("nodes[{}]", i), "is its own ancestor (the node hierarchy has a cycle)");
    }
  }
  // The scene's nodes, roots first then their descendants.
  std::vector<size_t> scene_nodes;
  {
    std::vector<size_t> roots;
    const json& scenes = d.root_array("scenes");
    if (!scenes.empty()) {
      const uint64_t si = d.uint(j, "scene", "scene", 0);
      const json& sc = d.item("scenes", si, "scene");
      if (sc.contains("nodes")) {
        if (!sc["nodes"].is_array()) d.fail(fmt::format("scenes[{}]", si), "\"nodes\" must be an array");
        for (const json& x : sc["nodes"]) {
          if (!x.is_number_unsigned() || x.get<uint64_t>() >= nn)
            d.fail(fmt::format("scenes[{}]", si), fmt::format("node {} is not a node index ({} nodes)", x.dump(), nn));
          roots.push_back(x.get<size_t>());
        }
      }
    } else {
      for (size_t i = 0; i < nn; ++i)
        if (out.nodes[i].parent < 0) roots.push_back(i);
    }
    std::vector<char> seen(nn, 0);
    std::vector<size_t> stack(roots.rbegin(), roots.rend());
    std::vector<std::vector<size_t>> children(nn);
    for (size_t i = 0; i < nn; ++i)
      if (out.nodes[i].parent >= 0) children[static_cast<size_t>(out.nodes[i].parent)].push_back(i);
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      if (seen[i]) continue;
      seen[i] = 1;
      scene_nodes.push_back(i);
      for (auto it = children[i].rbegin(); it != children[i].rend(); ++it) stack.push_back(*it);
    }
  }

  // The mesh nodes chosen.
  std::vector<size_t> chosen;
  std::set<std::string> names;
  for (size_t i : scene_nodes) {
    if (node_mesh[i] < 0) continue;
    const json& o = jnodes[i];
    const json& m = d.item("meshes", static_cast<uint64_t>(node_mesh[i]), fmt::format("nodes[{}]", i));
    const std::string node_name = d.string(o, "name", fmt::format("nodes[{}]", i), "");
    const std::string mesh_name = d.string(m, "name", fmt::format("meshes[{}]", node_mesh[i]), "");
    if (!node_name.empty()) names.insert(node_name);
    if (!mesh_name.empty()) names.insert(mesh_name);
    if (options.mesh_name.empty() || options.mesh_name == node_name || options.mesh_name == mesh_name)
      chosen.push_back(i);
  }
  auto list = [](const std::set<std::string>& s) {
    std::string l;
    for (const std::string& x : s) l += (l.empty() ? "'" : ", '") + x + "'";
    return l.empty() ? std::string("none") : l;
  };
  if (chosen.empty()) {
    throw InvalidInput(printable_message(
        options.mesh_name.empty()
            ? fmt::format("{}: the scene has no mesh node", path)
            : fmt::format("{}: no node or mesh of the scene is named '{}' (names: {})", path, options.mesh_name,
                          list(names))));
  }

  // Their primitives.
  std::map<uint64_t, int> skin_of_file;  // the file's skin index -> index into out.skins
  for (size_t ni : chosen) {
    const std::string nel = fmt::format("nodes[{}]", ni);
    int skin = -1;
    if (jnodes[ni].contains("skin")) {
      const uint64_t si = d.uint(jnodes[ni], "skin", nel);
      const auto found = skin_of_file.find(si);
      if (found != skin_of_file.end()) {
        skin = found->second;
      } else {
        out.skins.push_back(read_skin(d, si, nn, nel));
        skin = static_cast<int>(out.skins.size()) - 1;
        skin_of_file[si] = skin;
      }
    }
    const uint64_t mi = static_cast<uint64_t>(node_mesh[ni]);
    const json& m = d.item("meshes", mi, nel);
    const std::string mel = fmt::format("meshes[{}]", mi);
    if (!m.contains("primitives") || !m["primitives"].is_array() || m["primitives"].empty())
      d.fail(mel, "must have a non-empty \"primitives\" array");
    size_t n_targets = 0;
    for (size_t pi = 0; pi < m["primitives"].size(); ++pi) {
      const json& p = m["primitives"][pi];
      const std::string pel = fmt::format("{}.primitives[{}]", mel, pi);
      if (!p.is_object() || !p.contains("attributes") || !p["attributes"].is_object())
        d.fail(pel, "must be an object with \"attributes\"");
      const uint64_t mode = d.uint(p, "mode", pel, 4);
      if (mode < 4 || mode > 6) {
        d.fail(pel, fmt::format("mode {} (points or lines); only triangles (4, 5, 6) are a body surface: remove it "
                                "or choose the body with \"mesh_name\"",
                                mode));
      }
      const json& attrs = p["attributes"];
      if (!attrs.contains("POSITION")) d.fail(pel, "has no POSITION attribute");
      const Values pos = d.floats(d.uint(attrs, "POSITION", pel), "POSITION of " + pel, {"VEC3"}, false);
      const size_t nv = static_cast<size_t>(pos.count);
      GltfAnimatedMesh::Part part;
      part.node = static_cast<int>(ni);
      part.base.resize(nv);
      for (size_t v = 0; v < nv; ++v) part.base[v] = Vec3(pos.v[3 * v], pos.v[3 * v + 1], pos.v[3 * v + 2]);
      if (p.contains("targets")) {
        const json& ts = p["targets"];
        if (!ts.is_array()) d.fail(pel, "\"targets\" must be an array");
        for (size_t k = 0; k < ts.size(); ++k) {
          const std::string tel = fmt::format("{}.targets[{}]", pel, k);
          if (!ts[k].is_object()) d.fail(tel, "must be an object");
          std::vector<Vec3> disp(nv, Vec3::Zero());
          if (ts[k].contains("POSITION")) {
            const Values t = d.floats(d.uint(ts[k], "POSITION", tel), "POSITION of " + tel, {"VEC3"}, false);
            if (t.count != pos.count)
              d.fail(tel, fmt::format("POSITION has {} vertices, the primitive {}", t.count, pos.count));
            for (size_t v = 0; v < nv; ++v) disp[v] = Vec3(t.v[3 * v], t.v[3 * v + 1], t.v[3 * v + 2]);
          }
          part.targets.push_back(std::move(disp));
        }
      }
      std::vector<std::vector<std::pair<int, double>>> infl;  // skinned: per vertex
      if (skin >= 0) {
        part.skin = skin;
        infl = read_influences(d, attrs, pel, nv, out.skins[static_cast<size_t>(skin)].joints.size());
      }
      if (pi == 0) n_targets = part.targets.size();
      if (part.targets.size() != n_targets)
        d.fail(pel, fmt::format("has {} morph targets, primitive 0 of the mesh {}", part.targets.size(), n_targets));
      // Triangles.
      std::vector<uint32_t> idx;
      if (p.contains("indices")) {
        const Values iv =
            d.accessor(d.uint(p, "indices", pel), "indices of " + pel, {"SCALAR"}, {kUnsignedByte, kUnsignedShort, kUnsignedInt});
        idx.reserve(iv.v.size());
        for (double x : iv.v) {
          if (x >= static_cast<double>(nv))
            d.fail(pel, fmt::format("index {} is out of range (the primitive has {} vertices)", x, nv));
          idx.push_back(static_cast<uint32_t>(x));
        }
      } else {
        idx.resize(nv);
        std::iota(idx.begin(), idx.end(), 0u);
      }
      std::vector<std::array<int, 3>> tris;
      auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
        tris.push_back({static_cast<int>(a), static_cast<int>(b), static_cast<int>(c)});
      };
      if (mode == 4) {
        if (idx.size() % 3 != 0) d.fail(pel, fmt::format("{} indices is not a multiple of 3", idx.size()));
        for (size_t k = 0; k + 2 < idx.size(); k += 3) add(idx[k], idx[k + 1], idx[k + 2]);
      } else if (mode == 5) {
        for (size_t k = 0; k + 2 < idx.size(); ++k) {
          if (k % 2 == 0) add(idx[k], idx[k + 1], idx[k + 2]);
          else add(idx[k + 1], idx[k], idx[k + 2]);
        }
      } else {
        for (size_t k = 1; k + 1 < idx.size(); ++k) add(idx[0], idx[k], idx[k + 1]);
      }
      // Merge the vertices a seam split (same base, same displacements, same skin weights).
      std::vector<size_t> order(nv);
      std::iota(order.begin(), order.end(), size_t{0});
      auto key_less = [&](size_t a, size_t b) {
        for (int c = 0; c < 3; ++c)
          if (part.base[a][c] != part.base[b][c]) return part.base[a][c] < part.base[b][c];
        for (const auto& t : part.targets)
          for (int c = 0; c < 3; ++c)
            if (t[a][c] != t[b][c]) return t[a][c] < t[b][c];
        if (!infl.empty() && infl[a] != infl[b]) return infl[a] < infl[b];
        return a < b;
      };
      auto same = [&](size_t a, size_t b) {
        if (part.base[a] != part.base[b]) return false;
        for (const auto& t : part.targets)
          if (t[a] != t[b]) return false;
        return infl.empty() || infl[a] == infl[b];
      };
      std::sort(order.begin(), order.end(), key_less);  // equal keys: the first in file order first
      std::vector<size_t> first(nv);  // the first vertex of each one's equals
      for (size_t k = 0; k < nv; ++k)
        first[order[k]] = k > 0 && same(order[k], order[k - 1]) ? first[order[k - 1]] : order[k];
      std::vector<int> remap(nv, -1);  // new indices in file order
      std::vector<size_t> keep;
      for (size_t v = 0; v < nv; ++v) {
        if (first[v] == v) {
          remap[v] = static_cast<int>(keep.size());
          keep.push_back(v);
        }
      }
      for (size_t v = 0; v < nv; ++v) remap[v] = remap[first[v]];
      GltfAnimatedMesh::Part merged;
      merged.node = part.node;
      merged.skin = part.skin;
      merged.first_vertex = out.num_vertices;
      for (size_t v : keep) merged.base.push_back(part.base[v]);
      if (!infl.empty()) {
        merged.influence_start.push_back(0);
        for (size_t v : keep) {
          for (const auto& [j, w] : infl[v]) {
            merged.influence_joint.push_back(j);
            merged.influence_weight.push_back(w);
          }
          merged.influence_start.push_back(static_cast<int>(merged.influence_joint.size()));
        }
      }
      for (const auto& t : part.targets) {
        merged.targets.emplace_back();
        for (size_t v : keep) merged.targets.back().push_back(t[v]);
      }
      for (const auto& t : tris) {
        const int a = remap[static_cast<size_t>(t[0])], b = remap[static_cast<size_t>(t[1])],
                  c = remap[static_cast<size_t>(t[2])];
        if (a == b || b == c || a == c) continue;  // degenerate (strip restarts, merged seams)
        out.faces.push_back({a + merged.first_vertex, b + merged.first_vertex, c + merged.first_vertex});
      }
      if (merged.base.size() > static_cast<size_t>(std::numeric_limits<int>::max() - out.num_vertices))
        d.fail(pel, "too many vertices");
      out.num_vertices += static_cast<int>(merged.base.size());
      out.parts.push_back(std::move(merged));
    }
    // Default weights: the node's, else the mesh's, else 0.
    GltfAnimatedMesh::Node& n = out.nodes[ni];
    if (n.weights.empty() && m.contains("weights")) n.weights = d.numbers(m, "weights", mel, 0);
    if (n.weights.empty()) n.weights.assign(n_targets, 0.0);
    if (n.weights.size() != n_targets)
      d.fail(nel, fmt::format("has {} morph weights, its mesh {} targets", n.weights.size(), n_targets));
  }
  if (out.faces.empty())
    throw InvalidInput(fmt::format("{}: the chosen mesh nodes have no triangle (only degenerate ones)", path));

  // The animation.
  const json& anims = d.root_array("animations");
  int64_t ai = -1;
  std::set<std::string> anim_names;
  for (size_t i = 0; i < anims.size(); ++i) {
    const std::string name = anims[i].is_object() ? d.string(anims[i], "name", fmt::format("animations[{}]", i), "") : "";
    anim_names.insert(name.empty() ? fmt::format("#{}", i) : name);
    if (!options.animation.empty() && (name == options.animation || fmt::format("#{}", i) == options.animation))
      ai = static_cast<int64_t>(i);
  }
  if (!options.animation.empty() && ai < 0) {
    throw InvalidInput(printable_message(fmt::format("{}: no animation is named '{}' (animations: {})", path,
                                                     options.animation, list(anim_names))));
  }
  if (options.animation.empty() && anims.size() > 1) {
    throw InvalidInput(printable_message(fmt::format(
        "{}: the file has {} animations ({}); choose one with \"animation_name\"", path, anims.size(), list(anim_names))));
  }
  if (options.animation.empty() && anims.size() == 1) ai = 0;
  if (ai >= 0) {
    const json& a = d.item("animations", static_cast<uint64_t>(ai), "animations");
    const std::string ael = fmt::format("animations[{}]", ai);
    out.animation_name = d.string(a, "name", ael, fmt::format("#{}", ai));
    if (!a.contains("channels") || !a["channels"].is_array() || !a.contains("samplers") || !a["samplers"].is_array())
      d.fail(ael, "must have \"channels\" and \"samplers\" arrays");
    const json& samplers = a["samplers"];
    bool any = false;
    for (size_t ci = 0; ci < a["channels"].size(); ++ci) {
      const json& c = a["channels"][ci];
      const std::string cel = fmt::format("{}.channels[{}]", ael, ci);
      if (!c.is_object() || !c.contains("target") || !c["target"].is_object())
        d.fail(cel, "must be an object with \"sampler\" and \"target\"");
      const json& t = c["target"];
      const std::string path_name = d.string(t, "path", cel + ".target", "");
      if (!t.contains("node")) continue;  // the specification: ignore it
      GltfAnimatedMesh::Channel ch;
      const uint64_t node = d.uint(t, "node", cel + ".target");
      if (node >= nn) d.fail(cel, fmt::format("target node {} is not a node index ({} nodes)", node, nn));
      ch.node = static_cast<int>(node);
      if (path_name == "translation") ch.path = GltfAnimatedMesh::Path::Translation, ch.width = 3;
      else if (path_name == "rotation") ch.path = GltfAnimatedMesh::Path::Rotation, ch.width = 4;
      else if (path_name == "scale") ch.path = GltfAnimatedMesh::Path::Scale, ch.width = 3;
      else if (path_name == "weights") {
        ch.path = GltfAnimatedMesh::Path::Weights;
        if (node_mesh[node] < 0) d.fail(cel, fmt::format("animates the weights of nodes[{}], which has no mesh", node));
        const json& m = d.item("meshes", static_cast<uint64_t>(node_mesh[node]), cel);
        size_t nt = 0;
        if (m.contains("primitives") && m["primitives"].is_array() && !m["primitives"].empty() &&
            m["primitives"][0].is_object() && m["primitives"][0].contains("targets") &&
            m["primitives"][0]["targets"].is_array())
          nt = m["primitives"][0]["targets"].size();
        if (nt == 0) d.fail(cel, fmt::format("animates the weights of nodes[{}], whose mesh has no morph target", node));
        ch.width = static_cast<int>(nt);
      } else {
        d.fail(cel, fmt::format("target path '{}' is not read (translation, rotation, scale, weights)", path_name));
      }
      if (ch.path != GltfAnimatedMesh::Path::Weights && out.nodes[node].has_matrix)
        d.fail(cel, fmt::format("animates nodes[{}], which has a \"matrix\" (animated nodes must use TRS)", node));
      const uint64_t si = d.uint(c, "sampler", cel);
      if (si >= samplers.size() || !samplers[si].is_object())
        d.fail(cel, fmt::format("sampler {} is not a sampler of the animation ({} samplers)", si, samplers.size()));
      const json& s = samplers[si];
      const std::string sel = fmt::format("{}.samplers[{}]", ael, si);
      const std::string interp = d.string(s, "interpolation", sel, "LINEAR");
      if (interp == "LINEAR") ch.interpolation = GltfAnimatedMesh::Interpolation::Linear;
      else if (interp == "STEP") ch.interpolation = GltfAnimatedMesh::Interpolation::Step;
      else if (interp == "CUBICSPLINE") ch.interpolation = GltfAnimatedMesh::Interpolation::CubicSpline;
      else d.fail(sel, fmt::format("interpolation '{}' must be LINEAR, STEP or CUBICSPLINE", interp));
      const Values times = d.floats(d.uint(s, "input", sel), "input of " + sel, {"SCALAR"}, false);
      ch.times = times.v;
      for (size_t k = 1; k < ch.times.size(); ++k) {
        if (!(ch.times[k] > ch.times[k - 1]))
          d.fail(sel, fmt::format("key times must increase strictly (key {}: {} s after {} s)", k, ch.times[k],
                                  ch.times[k - 1]));
      }
      const bool norm_ok = ch.path == GltfAnimatedMesh::Path::Rotation || ch.path == GltfAnimatedMesh::Path::Weights;
      const char* type = ch.path == GltfAnimatedMesh::Path::Weights    ? "SCALAR"
                         : ch.path == GltfAnimatedMesh::Path::Rotation ? "VEC4"
                                                                       : "VEC3";
      const Values v = d.floats(d.uint(s, "output", sel), "output of " + sel, {type}, norm_ok);
      const uint64_t per_key = static_cast<uint64_t>(ch.width) *
                               (ch.interpolation == GltfAnimatedMesh::Interpolation::CubicSpline ? 3 : 1);
      if (v.v.size() != per_key * ch.times.size()) {
        d.fail(sel, fmt::format("output holds {} values; {} keys of {} values ({} interpolation) need {}", v.v.size(),
                                ch.times.size(), per_key, interp, per_key * ch.times.size()));
      }
      ch.values = v.v;
      if (ch.path == GltfAnimatedMesh::Path::Rotation && ch.interpolation != GltfAnimatedMesh::Interpolation::CubicSpline) {
        for (size_t k = 0; k < ch.times.size(); ++k) {
          const double* q = &ch.values[4 * k];
          if (!(std::abs(q[0]) + std::abs(q[1]) + std::abs(q[2]) + std::abs(q[3]) > 0))
            d.fail(sel, fmt::format("key {}: the rotation is not a unit quaternion (all zero)", k));
        }
      }
      out.start_s = any ? std::min(out.start_s, ch.times.front()) : ch.times.front();
      out.end_s = any ? std::max(out.end_s, ch.times.back()) : ch.times.back();
      any = true;
      out.channels.push_back(std::move(ch));
    }
  }
  return out;
}

namespace {

std::vector<double> sample(const GltfAnimatedMesh::Channel& c, double t) {
  using I = GltfAnimatedMesh::Interpolation;
  const size_t w = static_cast<size_t>(c.width), n = c.times.size();
  const bool cubic = c.interpolation == I::CubicSpline;
  auto value = [&](size_t k) {  // the key's value (cubic: the middle of its three)
    const size_t at = cubic ? (3 * k + 1) * w : k * w;
    return std::vector<double>(c.values.begin() + static_cast<std::ptrdiff_t>(at),
                               c.values.begin() + static_cast<std::ptrdiff_t>(at + w));
  };
  if (n == 1 || t <= c.times.front()) return value(0);
  if (t >= c.times.back()) return value(n - 1);
  const size_t k = static_cast<size_t>(std::upper_bound(c.times.begin(), c.times.end(), t) - c.times.begin()) - 1;
  const double td = c.times[k + 1] - c.times[k], s = (t - c.times[k]) / td;
  if (c.interpolation == I::Step) return value(k);
  std::vector<double> a = value(k), b = value(k + 1), r(w);
  if (c.interpolation == I::Linear) {
    if (c.path == GltfAnimatedMesh::Path::Rotation) {
      const Eigen::Quaterniond qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
      const Eigen::Quaterniond q = qa.normalized().slerp(s, qb.normalized());
      return {q.x(), q.y(), q.z(), q.w()};
    }
    for (size_t i = 0; i < w; ++i) r[i] = a[i] + s * (b[i] - a[i]);
    return r;
  }
  // Cubic Hermite: value and out-tangent of key k, in-tangent and value of k + 1.
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  for (size_t i = 0; i < w; ++i) {
    const double out_k = c.values[(3 * k + 2) * w + i], in_k1 = c.values[(3 * (k + 1)) * w + i];
    r[i] = h00 * a[i] + h10 * td * out_k + h01 * b[i] + h11 * td * in_k1;
  }
  if (c.path == GltfAnimatedMesh::Path::Rotation) {
    const double norm = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
    for (double& x : r) x /= norm;
  }
  return r;
}

}  // namespace

std::vector<Vec3> gltf_positions_at(const GltfAnimatedMesh& m, double t) {
  using P = GltfAnimatedMesh::Path;
  const size_t nn = m.nodes.size();
  // The local transform of every node at t, and its weights.
  std::vector<Eigen::Matrix4d> local(nn);
  std::vector<std::vector<double>> weights(nn);
  std::vector<Vec3> tr(nn), sc(nn);
  std::vector<Eigen::Quaterniond> rot(nn);
  for (size_t i = 0; i < nn; ++i) {
    const auto& n = m.nodes[i];
    tr[i] = n.translation;
    sc[i] = n.scale;
    rot[i] = Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]).normalized();
    weights[i] = n.weights;
  }
  for (const auto& c : m.channels) {
    const std::vector<double> v = sample(c, t);
    const size_t i = static_cast<size_t>(c.node);
    switch (c.path) {
      case P::Translation: tr[i] = Vec3(v[0], v[1], v[2]); break;
      case P::Scale: sc[i] = Vec3(v[0], v[1], v[2]); break;
      case P::Rotation: rot[i] = Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized(); break;
      case P::Weights: weights[i] = v; break;
    }
  }
  for (size_t i = 0; i < nn; ++i) {
    const auto& n = m.nodes[i];
    if (n.has_matrix) {
      local[i] = Eigen::Map<const Eigen::Matrix4d>(n.matrix.data());  // column-major
    } else {
      local[i].setIdentity();
      local[i].topLeftCorner<3, 3>() = rot[i].toRotationMatrix() * sc[i].asDiagonal();
      local[i].topRightCorner<3, 1>() = tr[i];
    }
  }
  // Global transforms: a node's parents' local transforms times its own.
  std::vector<Eigen::Matrix4d> global(nn);
  std::vector<char> done(nn, 0);
  for (size_t i = 0; i < nn; ++i) {
    std::vector<size_t> chain;  // i and its ancestors not yet done, i first
    for (int p = static_cast<int>(i); p >= 0 && !done[static_cast<size_t>(p)]; p = m.nodes[static_cast<size_t>(p)].parent)
      chain.push_back(static_cast<size_t>(p));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int parent = m.nodes[*it].parent;
      global[*it] = parent >= 0 ? Eigen::Matrix4d(global[static_cast<size_t>(parent)] * local[*it]) : local[*it];
      done[*it] = 1;
    }
  }
  // Each skin's joint matrices: the joint's global transform times its inverse bind matrix.
  std::vector<std::vector<Eigen::Matrix4d>> joint_matrices(m.skins.size());
  for (size_t s = 0; s < m.skins.size(); ++s) {
    const auto& skin = m.skins[s];
    for (size_t j = 0; j < skin.joints.size(); ++j)
      joint_matrices[s].push_back(global[static_cast<size_t>(skin.joints[j])] *
                                  Eigen::Map<const Eigen::Matrix4d>(skin.inverse_bind[j].data()));
  }
  std::vector<Vec3> out(static_cast<size_t>(m.num_vertices));
  for (const auto& part : m.parts) {
    const Eigen::Matrix4d& g = global[static_cast<size_t>(part.node)];
    const std::vector<double>& w = weights[static_cast<size_t>(part.node)];
    const Eigen::Matrix3d A = g.topLeftCorner<3, 3>();
    const Vec3 b = g.topRightCorner<3, 1>();
    std::vector<size_t> active;  // targets with a weight (one of them for our own files)
    for (size_t k = 0; k < part.targets.size() && k < w.size(); ++k)
      if (w[k] != 0.0) active.push_back(k);
    for (size_t v = 0; v < part.base.size(); ++v) {
      Vec3 x = part.base[v];
      for (size_t k : active) x += w[k] * part.targets[k][v];
      Vec3 y = Vec3::Zero();
      if (part.skin >= 0) {  // linear blend skinning; the node's own transform is ignored
        const auto& J = joint_matrices[static_cast<size_t>(part.skin)];
        for (int e = part.influence_start[v]; e < part.influence_start[v + 1]; ++e) {
          const Eigen::Matrix4d& M = J[static_cast<size_t>(part.influence_joint[static_cast<size_t>(e)])];
          y += part.influence_weight[static_cast<size_t>(e)] * (M.topLeftCorner<3, 3>() * x + M.topRightCorner<3, 1>());
        }
      } else {
        y = A * x + b;
      }
      if (!y.allFinite()) {
        throw InvalidInput(fmt::format("{}: at {} s a vertex of nodes[{}] is not finite (the transforms overflow)",
                                       m.path, t, part.node));
      }
      out[static_cast<size_t>(part.first_vertex) + v] = y;
    }
  }
  return out;
}

}  // namespace knitforge
