// knitforge shape: writes a built-in surface as a triangle mesh.
#include <cstdio>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge::cli {

void add_shape_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "shape", "Write a built-in surface (hemisphere, triple-peak, ...) as a mesh file");
  auto name = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto edge = std::make_shared<double>(kDefaultShapeEdgeLength);
  auto list = std::make_shared<bool>(false);
  const std::string names = shape_name_list();
  cmd->add_option("name", *name, "Shape name: " + names);
  cmd->add_option("-o,--output", *output, "Output mesh (.obj, .ply)");
  cmd->add_option("--edge", *edge, "Target edge length of the triangulation (mm)")
      ->check(positive_number());
  cmd->add_flag("--list", *list, "List the shape names and exit");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      if (*list) {
        for (const auto& n : shape_names()) std::printf("%s\n", n.c_str());
        return 0;
      }
      if (name->empty() || output->empty()) {
        throw UsageError("shape: give a shape name and -o FILE (see 'knitforge shape --list')");
      }
      check_output_file("-o", *output, {".obj", ".ply", ".off", ".stl"});
      const TriMesh mesh = make_shape(*name, *edge);
      write_mesh(*output, mesh);
      const BoundingBox box = bounding_box(mesh);
      const Vec3 size = box.max - box.min;
      note(fmt::format("{}: {} vertices, {} triangles, {:.1f} x {:.1f} x {:.1f} mm -> {}", *name,
                       mesh.num_vertices(), mesh.num_faces(), size.x(), size.y(), size.z(), *output));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
