#pragma once
// Helpers for the io tests: a scratch directory, file writing, small meshes,
// and checks on IOError messages.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <unistd.h>

#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/util/errors.h"

namespace knitforge::test {

/// A fresh directory removed at destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    dir_ = std::filesystem::temp_directory_path() /
           ("knitforge_io_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  /// Writes `content` byte for byte and returns the path.
  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p;
  }
  std::string read(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  size_t num_files() const {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir_), {}));
  }

 private:
  std::filesystem::path dir_;
};

/// The message of the IOError `f` throws; a test failure when it throws
/// nothing or something else.
inline std::string io_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const IOError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected IOError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected IOError, nothing was thrown";
  return {};
}

/// Same for InvalidInput.
inline std::string invalid_input(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InvalidInput, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InvalidInput, nothing was thrown";
  return {};
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

/// An n x m grid of squares split into triangles, with coordinates that are
/// not short decimals (so lossless writing is tested).
inline TriMesh grid_mesh(int n = 3, int m = 2) {
  TriMesh mesh;
  for (int j = 0; j <= m; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.vertices.emplace_back(i / 3.0 + 1e-13 * j, j * 0.1 + 1.0 / 7.0, std::sin(i * 0.7 + j) * 1e3);
    }
  }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

/// The same grid with coordinates exactly representable as floats (for STL).
inline TriMesh float_grid_mesh(int n = 3, int m = 2) {
  TriMesh mesh = grid_mesh(n, m);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    mesh.vertices[v] = Vec3((v % (n + 1)) * 0.25, (v / (n + 1)) * 1.5, v * 0.125 - 1.0);
  }
  return mesh;
}

/// Bitwise equality of vertex arrays and equality of faces.
inline void expect_same_mesh(const TriMesh& a, const TriMesh& b) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  for (int v = 0; v < a.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.vertices[v][k], b.vertices[v][k]) << "vertex " << v;
  }
  for (int f = 0; f < a.num_faces(); ++f) EXPECT_EQ(a.faces[f], b.faces[f]) << "face " << f;
}

}  // namespace knitforge::test
