#include "knitforge/io/mesh_io.h"

#include <filesystem>

#include <fmt/core.h>

#include "knitforge/io/io_detail.h"
#include "knitforge/io/obj.h"
#include "knitforge/io/off.h"
#include "knitforge/io/ply.h"
#include "knitforge/io/stl.h"
#include "knitforge/util/errors.h"

namespace knitforge {

TriMesh read_mesh(const std::string& path) {
  {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      throw IOError(fmt::format("{}: is a directory, not a mesh file", path));
    }
  }
  const std::string ext = io_detail::extension(path);
  if (ext == "obj") return read_obj(path);
  if (ext == "ply") return read_ply(path);
  if (ext == "off") return read_off(path);
  if (ext == "stl") return read_stl(path);
  throw IOError(fmt::format("{}: unknown mesh format '.{}'; use .obj, .ply, .off or .stl", path, ext));
}

void write_mesh(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options) {
  const std::string ext = io_detail::extension(path);
  if (ext == "obj") return write_obj(path, mesh, options);
  if (ext == "ply") return write_ply(path, mesh, options);
  if (ext == "off") return write_off(path, mesh, options);
  if (ext == "stl") return write_stl(path, mesh, options);
  throw InvalidInput(
      fmt::format("{}: unknown mesh format '.{}'; use .obj, .ply, .off or .stl", path, ext));
}

}  // namespace knitforge
