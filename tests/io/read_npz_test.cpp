// The .npz reader: ZIP entries stored, deflated and ZIP64; .npy versions,
// dtypes, Fortran order; every malformed input refused naming the entry.
#include "knitforge/io/read_npz.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"
#include "io/npz_test_writer.h"

using namespace knitforge;
using namespace knitforge::test;

namespace {

const std::vector<double> kSix = {1.5, -2.25, 3.0, 4e-300, -0.0, 1e10};

std::string two_arrays(bool deflate, bool zip64 = false) {
  return zip_bytes({{"a.npy", npy_f8({2, 3}, kSix), deflate},
                    {"ids.npy", npy_bytes("<u4", {3}, raw_bytes<uint32_t>(std::vector<uint32_t>{7, 4294967295u, 0})),
                     deflate}},
                   zip64);
}

void expect_two_arrays(const std::string& path) {
  const auto arrays = read_npz(path);
  ASSERT_EQ(arrays.size(), 2u);
  const NpyArray& a = arrays.at("a");
  EXPECT_EQ(a.dtype, "<f8");
  EXPECT_EQ(a.shape, (std::vector<int64_t>{2, 3}));
  EXPECT_FALSE(a.is_integer);
  ASSERT_EQ(a.doubles.size(), 6u);
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(a.doubles[i], kSix[i]) << i;
  const NpyArray& ids = arrays.at("ids");
  EXPECT_TRUE(ids.is_integer);
  EXPECT_EQ(ids.ints, (std::vector<int64_t>{7, 4294967295LL, 0}));
  EXPECT_EQ(ids.shape_text(), "(3,)");
}

}  // namespace

TEST(ReadNpz, ReadsStoredDeflatedAndZip64Entries) {
  TempDir dir;
  expect_two_arrays(dir.write("stored.npz", two_arrays(false)));
  expect_two_arrays(dir.write("deflated.npz", two_arrays(true)));
  expect_two_arrays(dir.write("zip64.npz", two_arrays(true, true)));
  // The deflated archive really is compressed differently (not stored).
  EXPECT_NE(two_arrays(false).size(), two_arrays(true).size());
}

TEST(ReadNpz, ListsEntriesAndReadsOnDemand) {
  TempDir dir;
  const std::string p = dir.write("m.npz", zip_bytes({{"x.npy", npy_f8({1}, {2.0})},
                                                      {"s.npy", npy_bytes("<U3", {}, std::string(12, 'a'))}}));
  const NpzReader r(p);
  EXPECT_EQ(r.names(), (std::vector<std::string>{"x", "s"}));
  EXPECT_TRUE(r.contains("x"));
  EXPECT_FALSE(r.contains("y"));
  EXPECT_EQ(r.read("x").doubles, std::vector<double>{2.0});  // the string array is never read
  const std::string m = io_error([&] { r.read("s"); });
  EXPECT_CONTAINS(m, "entry 's.npy'");
  EXPECT_CONTAINS(m, "unsupported dtype '<U3'");
  EXPECT_CONTAINS(io_error([&] { r.read("y"); }), "no such array in the file (it has: x, s)");
}

TEST(ReadNpz, EveryDtypeAndHeaderVersion) {
  TempDir dir;
  const std::vector<int64_t> v = {0, 1, 200, 7};
  std::vector<ZipEntry> e = {
      {"f4.npy", npy_bytes("<f4", {4}, raw_bytes<float>(std::vector<float>{0.5f, -1.0f, 3.25f, 1e30f}))},
      {"i4.npy", npy_bytes("<i4", {4}, raw_bytes<int32_t>(std::vector<int32_t>{-5, 1, 2147483647, -2147483647 - 1}))},
      {"i8.npy", npy_bytes("<i8", {4}, raw_bytes<int64_t>(std::vector<int64_t>{-1, 0, 1LL << 40, 3}), false, 2)},
      {"u8.npy", npy_bytes("<u8", {4}, raw_bytes<uint64_t>(v), false, 3)},
      {"u1.npy", npy_bytes("|u1", {4}, raw_bytes<uint8_t>(v))},
      {"b1.npy", npy_bytes("|b1", {4}, raw_bytes<uint8_t>(std::vector<int>{1, 0, 0, 1}))},
      {"scalar.npy", npy_bytes("<f8", {}, raw_bytes<double>(std::vector<double>{42.0}))},
      {"empty.npy", npy_bytes("<f8", {0, 3}, "")},
  };
  const auto a = read_npz(dir.write("t.npz", zip_bytes(e)));
  EXPECT_EQ(a.at("f4").doubles, (std::vector<double>{0.5, -1.0, 3.25, static_cast<double>(1e30f)}));
  EXPECT_EQ(a.at("i4").ints, (std::vector<int64_t>{-5, 1, 2147483647, -2147483648LL}));
  EXPECT_EQ(a.at("i8").ints, (std::vector<int64_t>{-1, 0, 1LL << 40, 3}));
  EXPECT_EQ(a.at("u8").ints, v);
  EXPECT_EQ(a.at("u1").ints, v);
  EXPECT_EQ(a.at("b1").ints, (std::vector<int64_t>{1, 0, 0, 1}));
  EXPECT_EQ(a.at("scalar").size(), 1);
  EXPECT_EQ(a.at("scalar").doubles, std::vector<double>{42.0});
  EXPECT_EQ(a.at("empty").size(), 0);
  EXPECT_EQ(a.at("empty").shape_text(), "(0, 3)");
}

TEST(ReadNpz, FortranOrderIsConvertedToCOrder) {
  TempDir dir;
  // A 2 x 3 x 2 array a[i][j][k] = 100 i + 10 j + k, written column-major.
  std::vector<double> fortran;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i) fortran.push_back(100 * i + 10 * j + k);
  const auto a = read_npz(dir.write("f.npz", zip_bytes({{"a.npy", npy_bytes("<f8", {2, 3, 2}, raw_bytes<double>(fortran), true)}})));
  const NpyArray& x = a.at("a");
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 2; ++k) EXPECT_EQ(x.doubles[static_cast<size_t>((i * 3 + j) * 2 + k)], 100 * i + 10 * j + k);
}

TEST(ReadNpz, RefusesBigEndianObjectAndStructuredArrays) {
  TempDir dir;
  std::string m = io_error([&] {
    read_npz(dir.write("be.npz", zip_bytes({{"v.npy", npy_bytes(">f8", {1}, std::string(8, '\0'))}})));
  });
  EXPECT_CONTAINS(m, "be.npz: entry 'v.npy'");
  EXPECT_CONTAINS(m, "big-endian");
  m = io_error([&] { read_npz(dir.write("o.npz", zip_bytes({{"J_regressor.npy", npy_bytes("|O", {}, "\x80\x02N.")}}))); });
  EXPECT_CONTAINS(m, "entry 'J_regressor.npy'");
  EXPECT_CONTAINS(m, "Python objects");
  EXPECT_CONTAINS(m, "convert");
  std::string hdr = npy_bytes("<f8", {1}, std::string(8, '\0'));
  const size_t at = hdr.find("'<f8'");
  hdr.replace(at, 5, "[('a', '<f8')]");
  m = io_error([&] { read_npz(dir.write("s.npz", zip_bytes({{"r.npy", hdr}}))); });
  EXPECT_CONTAINS(m, "structured arrays");
}

TEST(ReadNpz, RefusesMalformedArchives) {
  TempDir dir;
  const std::string good = two_arrays(true);
  // Truncated: the end record is gone.
  std::string m = io_error([&] { read_npz(dir.write("cut.npz", good.substr(0, good.size() / 2))); });
  EXPECT_CONTAINS(m, "cut.npz: byte");
  EXPECT_CONTAINS(m, "end-of-central-directory");
  EXPECT_CONTAINS(io_error([&] { read_npz(dir.write("short.npz", "PK")); }), "too short");
  EXPECT_CONTAINS(io_error([&] { read_npz(dir.path("missing.npz")); }), "cannot open");
  // A corrupted byte in the deflated data of the first entry: zlib or the CRC notices.
  std::string bad = good;
  bad[60] = static_cast<char>(bad[60] ^ 0x5A);
  m = io_error([&] { read_npz(dir.write("flip.npz", bad)); });
  EXPECT_CONTAINS(m, "entry 'a.npy'");
  // A stored entry whose bytes changed: the CRC.
  std::string stored = two_arrays(false);
  const size_t data_at = stored.find("\x93NUMPY");
  stored[data_at + 130] = static_cast<char>(stored[data_at + 130] ^ 1);  // in a's 48 data bytes
  m = io_error([&] { read_npz(dir.write("crc.npz", stored)); });
  EXPECT_CONTAINS(m, "entry 'a.npy'");
  EXPECT_CONTAINS(m, "CRC-32");
  // Entries that are not arrays, and duplicates.
  EXPECT_CONTAINS(io_error([&] { read_npz(dir.write("txt.npz", zip_bytes({{"notes.txt", "hi"}}))); }),
                  "entry 'notes.txt': is not a .npy array");
  EXPECT_CONTAINS(io_error([&] {
                    read_npz(dir.write("dup.npz", zip_bytes({{"a.npy", npy_f8({1}, {1})}, {"a.npy", npy_f8({1}, {2})}})));
                  }),
                  "appears twice");
}

TEST(ReadNpz, RefusesBadNpyHeadersAndSizes) {
  TempDir dir;
  auto refuse = [&](const std::string& npy, const std::string& expect) {
    const std::string m = io_error([&] { read_npz(dir.write("h.npz", zip_bytes({{"arr.npy", npy, true}}))); });
    EXPECT_CONTAINS(m, "h.npz: entry 'arr.npy'");
    EXPECT_CONTAINS(m, expect);
  };
  refuse("NUMPY\x01\x00", "no \\x93NUMPY magic");
  std::string v = npy_f8({1}, {1.0});
  v[6] = 4;
  refuse(v, "version 4.0 is not supported");
  v = npy_f8({1}, {1.0});
  v[8] = static_cast<char>(0xFF);  // header length past the end
  v[9] = 0x7F;
  refuse(v, "header claims");
  v = npy_f8({1}, {1.0});
  v.replace(v.find("'shape'"), 7, "'shapf'");
  refuse(v, "unknown key 'shapf'");
  v = npy_f8({1}, {1.0});
  v.replace(v.find("False"), 5, "Maybe");
  refuse(v, "neither True nor False");
  // The shape describes more (or fewer) bytes than the entry holds, refused
  // before anything is allocated: here 2^60 elements.
  refuse(npy_bytes("<f8", {1LL << 30, 1LL << 30}, std::string(16, '\0')), "needs more than the 16 data bytes");
  refuse(npy_bytes("<f8", {3}, std::string(16, '\0')), "needs more than the 16 data bytes");
  refuse(npy_bytes("<f8", {1}, std::string(16, '\0')), "is 8 bytes, the entry has 16 data bytes");
  refuse(npy_bytes("|b1", {1}, std::string(1, '\2')), "not 0 or 1");
  refuse(npy_bytes("<u8", {1}, std::string(8, '\xFF')), "beyond the int64 range");
}

TEST(ReadNpz, RefusesEntriesLargerThanTheLimitOrTheirCompressedBytes) {
  TempDir dir;
  const std::string p = dir.write("big.npz", zip_bytes({{"a.npy", npy_f8({100}, std::vector<double>(100, 0.0)), true}}));
  NpzReadOptions o;
  o.max_entry_bytes = 500;
  EXPECT_CONTAINS(io_error([&] { NpzReader r(p, o); }), "more than the limit of 500 bytes");
  // A stored entry claiming another uncompressed size than its stored bytes.
  std::string z = zip_bytes({{"a.npy", npy_f8({2}, {1, 2})}});
  const size_t cd = z.find(std::string("PK\x01\x02", 4));
  z[cd + 24] = static_cast<char>(z[cd + 24] + 1);
  EXPECT_CONTAINS(io_error([&] { read_npz(dir.write("lie.npz", z)); }), "which the stored method cannot give");
}

TEST(ReadNpz, ReadsArchivesOfPythonsZipfile) {
  // The seeds of fuzz_npz, written by CPython's zipfile (numpy.savez's
  // writer) through fuzz/make_npz_seeds.py: another ZIP writer than ours,
  // including numpy's force_zip64 local headers.
  const std::string seeds = std::string(KNITFORGE_TESTS_DIR) + "/../fuzz/corpus/fuzz_npz/";
  const auto z = read_npz(seeds + "zip64_deflated.npz");
  EXPECT_EQ(z.at("a").doubles, (std::vector<double>{1.5, -2.25, 3.0, 4.0, 5.0, 6.0}));
  EXPECT_EQ(z.at("fortran").doubles, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  const auto d = read_npz(seeds + "dtypes_deflated.npz");
  EXPECT_EQ(d.at("i4").ints, (std::vector<int64_t>{-1, 0, 7}));
  EXPECT_EQ(d.at("u8").ints, (std::vector<int64_t>{1, 1LL << 40}));
  EXPECT_EQ(d.at("u1").ints, (std::vector<int64_t>{1, 3, 2, 4}));
  EXPECT_EQ(d.at("b1").ints, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(d.at("scalar").doubles, std::vector<double>{2.5});
  const auto s = read_npz(seeds + "smpl_like_stored.npz");
  EXPECT_EQ(s.at("kintree_table").ints, (std::vector<int64_t>{4294967295LL, 0, 0, 1}));
  EXPECT_EQ(s.at("weights").doubles[3], 0.5);
  EXPECT_EQ(s.at("f").shape, (std::vector<int64_t>{4, 3}));
}
