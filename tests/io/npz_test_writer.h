#pragma once
// A small writer of NumPy .npy arrays and .npz (ZIP) archives for the tests
// of read_npz and of the SMPL-format model loader: entries stored or
// deflated (zlib), optionally with ZIP64 records, and every byte reachable
// so that tests can corrupt it.

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace knitforge::test {

template <class T>
void put_le(std::string& out, T v) {
  for (size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<char>((static_cast<uint64_t>(v) >> (8 * i)) & 0xFF));
}

/// The raw little-endian bytes of `values` as type T.
template <class T, class U>
std::string raw_bytes(const std::vector<U>& values) {
  std::string out;
  for (const U& u : values) {
    const T v = static_cast<T>(u);
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));  // the test machines are little-endian
  }
  return out;
}

/// A .npy file: magic, version, header dictionary padded to 64 bytes, data.
inline std::string npy_bytes(const std::string& descr, const std::vector<int64_t>& shape, const std::string& data,
                             bool fortran = false, int major = 1) {
  std::string dims;
  for (size_t d = 0; d < shape.size(); ++d) dims += (d ? ", " : "") + std::to_string(shape[d]);
  if (shape.size() == 1) dims += ",";
  std::string header = "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
                       ", 'shape': (" + dims + "), }";
  const size_t prefix = major == 1 ? 10 : 12;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out.push_back(static_cast<char>(major));
  out.push_back(0);
  if (major == 1) put_le<uint16_t>(out, static_cast<uint16_t>(header.size()));
  else put_le<uint32_t>(out, static_cast<uint32_t>(header.size()));
  return out + header + data;
}

inline std::string npy_f8(const std::vector<int64_t>& shape, const std::vector<double>& v) {
  return npy_bytes("<f8", shape, raw_bytes<double>(v));
}
inline std::string npy_i8(const std::vector<int64_t>& shape, const std::vector<int64_t>& v) {
  return npy_bytes("<i8", shape, raw_bytes<int64_t>(v));
}

/// One archive entry: its name (with ".npy") and bytes.
struct ZipEntry {
  std::string name;
  std::string data;
  bool deflate = false;
};

inline std::string raw_deflate(const std::string& data) {
  z_stream z{};
  if (deflateInit2(&z, 6, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw std::runtime_error("zlib");
  std::string out(deflateBound(&z, static_cast<uLong>(data.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  if (deflate(&z, Z_FINISH) != Z_STREAM_END) throw std::runtime_error("zlib deflate");
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

/// A ZIP archive of the entries. zip64: sizes and offsets as 0xFFFFFFFF with
/// ZIP64 extra fields, and a ZIP64 end record (as numpy's force_zip64 and
/// archives over 4 GB).
inline std::string zip_bytes(const std::vector<ZipEntry>& entries, bool zip64 = false) {
  std::string out, central;
  for (const ZipEntry& e : entries) {
    const uint32_t crc = static_cast<uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(e.data.data()), static_cast<uInt>(e.data.size())));
    const std::string payload = e.deflate ? raw_deflate(e.data) : e.data;
    const uint64_t offset = out.size();
    const uint16_t method = e.deflate ? 8 : 0;
    std::string extra;
    if (zip64) {
      put_le<uint16_t>(extra, 1);
      put_le<uint16_t>(extra, 16);
      put_le<uint64_t>(extra, e.data.size());
      put_le<uint64_t>(extra, payload.size());
    }
    put_le<uint32_t>(out, 0x04034b50);
    put_le<uint16_t>(out, zip64 ? 45 : 20);
    put_le<uint16_t>(out, 0);
    put_le<uint16_t>(out, method);
    put_le<uint32_t>(out, 0);  // time, date
    put_le<uint32_t>(out, crc);
    put_le<uint32_t>(out, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(payload.size()));
    put_le<uint32_t>(out, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(e.data.size()));
    put_le<uint16_t>(out, static_cast<uint16_t>(e.name.size()));
    put_le<uint16_t>(out, static_cast<uint16_t>(extra.size()));
    out += e.name + extra + payload;

    std::string cextra;
    if (zip64) {
      put_le<uint16_t>(cextra, 1);
      put_le<uint16_t>(cextra, 24);
      put_le<uint64_t>(cextra, e.data.size());
      put_le<uint64_t>(cextra, payload.size());
      put_le<uint64_t>(cextra, offset);
    }
    put_le<uint32_t>(central, 0x02014b50);
    put_le<uint16_t>(central, zip64 ? 45 : 20);
    put_le<uint16_t>(central, zip64 ? 45 : 20);
    put_le<uint16_t>(central, 0);
    put_le<uint16_t>(central, method);
    put_le<uint32_t>(central, 0);
    put_le<uint32_t>(central, crc);
    put_le<uint32_t>(central, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(payload.size()));
    put_le<uint32_t>(central, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(e.data.size()));
    put_le<uint16_t>(central, static_cast<uint16_t>(e.name.size()));
    put_le<uint16_t>(central, static_cast<uint16_t>(cextra.size()));
    put_le<uint16_t>(central, 0);  // comment
    put_le<uint16_t>(central, 0);  // disk
    put_le<uint16_t>(central, 0);  // internal attributes
    put_le<uint32_t>(central, 0);  // external attributes
    put_le<uint32_t>(central, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(offset));
    central += e.name + cextra;
  }
  const uint64_t cd_offset = out.size();
  out += central;
  if (zip64) {
    const uint64_t rec = out.size();
    put_le<uint32_t>(out, 0x06064b50);
    put_le<uint64_t>(out, 44);
    put_le<uint16_t>(out, 45);
    put_le<uint16_t>(out, 45);
    put_le<uint32_t>(out, 0);
    put_le<uint32_t>(out, 0);
    put_le<uint64_t>(out, entries.size());
    put_le<uint64_t>(out, entries.size());
    put_le<uint64_t>(out, central.size());
    put_le<uint64_t>(out, cd_offset);
    put_le<uint32_t>(out, 0x07064b50);
    put_le<uint32_t>(out, 0);
    put_le<uint64_t>(out, rec);
    put_le<uint32_t>(out, 1);
  }
  put_le<uint32_t>(out, 0x06054b50);
  put_le<uint16_t>(out, 0);
  put_le<uint16_t>(out, 0);
  put_le<uint16_t>(out, zip64 ? 0xFFFF : static_cast<uint16_t>(entries.size()));
  put_le<uint16_t>(out, zip64 ? 0xFFFF : static_cast<uint16_t>(entries.size()));
  put_le<uint32_t>(out, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(central.size()));
  put_le<uint32_t>(out, zip64 ? 0xFFFFFFFF : static_cast<uint32_t>(cd_offset));
  put_le<uint16_t>(out, 0);
  return out;
}

}  // namespace knitforge::test
