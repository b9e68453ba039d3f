#pragma once
/// \file read_npz.h
/// NumPy's `.npz` files: a ZIP archive with one `.npy` array per entry (what
/// `numpy.savez` and `numpy.savez_compressed` write). Read by the SMPL-format
/// body model loader (body/smpl_model_npz.h); formats only, nothing about
/// bodies here.
///
/// ZIP: entries stored (method 0) or deflated (method 8, zlib), sizes and
/// offsets taken from the central directory (ZIP64 records and extra fields
/// are understood, so files over 4 GB and numpy's `force_zip64` entries
/// read), CRC-32 checked. No encryption, no multi-disk archives.
///
/// NPY: format versions 1.0, 2.0 and 3.0; the header dictionary's keys
/// 'descr', 'fortran_order' and 'shape'. Element types: little-endian
/// `<f8 <f4 <i4 <i8 <u4 <u8` and the byte types `|u1 |b1` (`<` or `=`/`|`
/// for one byte). Big-endian arrays (`>f8`) and object arrays (`|O`, what
/// numpy writes for Python objects such as the chumpy and scipy.sparse
/// arrays of SMPL's original pickles) are refused with what to do. Fortran
/// order is converted to C order on reading.
///
/// Bounded: an entry's declared size must fit its compressed bytes (deflate
/// expands at most 1032-fold) and `NpzReadOptions::max_entry_bytes`, and an
/// array's shape must describe exactly the bytes after its header, all
/// checked before anything is allocated.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace knitforge {

/// One array of an `.npz` (or `.npy`) file, in C (row-major) order.
struct NpyArray {
  std::string dtype;            ///< as written in the file, e.g. "<f8", "|b1"
  std::vector<int64_t> shape;   ///< empty for a 0-d array (one element)
  bool is_integer = false;      ///< integer or bool dtype: values are in `ints`
  std::vector<double> doubles;  ///< the values of a float array (size())
  std::vector<int64_t> ints;    ///< the values of an integer or bool array (size())

  /// Number of elements (the product of the shape; 1 for a 0-d array).
  int64_t size() const;
  /// Element `i` (C order) as a double, whatever the dtype.
  double value(int64_t i) const { return is_integer ? static_cast<double>(ints[static_cast<size_t>(i)]) : doubles[static_cast<size_t>(i)]; }
  /// "(6890, 3)": the shape as numpy prints it.
  std::string shape_text() const;
};

/// Limits of the reader.
struct NpzReadOptions {
  /// Largest uncompressed entry (bytes); larger ones are refused before
  /// they are read. 2 GiB: SMPL-X's posedirs (the largest array of the
  /// published models) is about 120 MB in float64.
  uint64_t max_entry_bytes = uint64_t{1} << 31;
};

/// An `.npz` file whose directory has been read: lists the arrays and reads
/// any of them on demand (a model file may hold arrays its reader does not
/// need and cannot read, such as strings).
class NpzReader {
 public:
  /// Opens `path` and reads its ZIP central directory.
  /// \throw IOError naming the file (and byte offset) when it cannot be
  ///        read, is not a ZIP archive, uses an unsupported ZIP feature, or
  ///        has an entry that does not end in ".npy", a duplicate name or
  ///        an entry reaching past the end of the file.
  explicit NpzReader(const std::string& path, const NpzReadOptions& options = {});

  /// The array names in archive order (entry names without ".npy").
  const std::vector<std::string>& names() const { return names_; }
  bool contains(const std::string& name) const;
  /// Reads one array. \throw IOError "<path>: entry '<name>.npy': <what is
  /// wrong>" for an unknown name, a corrupt entry (bad compressed data,
  /// CRC, sizes) or an invalid or unsupported `.npy` header.
  NpyArray read(const std::string& name) const;
  const std::string& path() const { return path_; }

 private:
  struct Entry {
    std::string name;  // without ".npy"
    uint16_t method = 0;
    uint32_t crc = 0;
    uint64_t compressed = 0, uncompressed = 0, local_offset = 0;
  };
  std::string path_;
  NpzReadOptions options_;
  uint64_t file_size_ = 0;
  std::vector<Entry> entries_;
  std::vector<std::string> names_;
};

/// Every array of an `.npz` file by name. \throw IOError as NpzReader.
std::map<std::string, NpyArray> read_npz(const std::string& path, const NpzReadOptions& options = {});

/// Parses the bytes of one `.npy` file; `what` names it in messages
/// ("model.npz: entry 'f.npy'"). \throw IOError "<what>: <problem>".
NpyArray parse_npy(const std::string& bytes, const std::string& what);

}  // namespace knitforge
