// knitforge support / close / thicken: shape utilities for fabrication
// (seed §2.C): a support object for a knitted sample, an alpha-wrap closing
// of a mesh, and thickening of an open surface into a solid.
#include <memory>
#include <string>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/geometry/alpha_close.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/geometry/support_object.h"
#include "knitforge/geometry/thicken_surface.h"
#include "knitforge/io/mesh_io.h"

namespace knitforge::cli {

namespace {

std::string shape_list() {
  const std::string names = shape_name_list();
  return names;
}

/// Common options: INPUT, -o, --units, --edge.
struct Common {
  std::string input, output, units = "mm";
  double edge = kDefaultShapeEdgeLength;
};

/// The output check of the three commands (before any work).
void check_common(const Common& c) {
  check_output_file("-o", c.output, {".stl", ".ply", ".obj", ".off"}, {c.input});
}

void add_common(CLI::App& cmd, Common& c, const std::string& output_help) {
  cmd.add_option("input", c.input, "Surface mesh (.obj/.ply/.off/.stl) or a built-in shape: " + shape_list())
      ->required();
  cmd.add_option("-o,--output", c.output, output_help)->required();
  cmd.add_option("--units", c.units, "Units of the input mesh: mm, cm, m (outputs are in mm)");
  cmd.add_option("--edge", c.edge, "Edge length (mm) of a built-in shape's triangulation")
      ->check(positive_number());
}

std::string size_text(const TriMesh& mesh) {
  const Vec3 s = bounding_box(mesh).size();
  return fmt::format("{} vertices, {} triangles, {:.5g} x {:.5g} x {:.5g} mm, volume {:.6g} mm^3",
                     mesh.num_vertices(), mesh.num_faces(), s.x(), s.y(), s.z(), enclosed_volume(mesh));
}

void warn_flips(int flipped, const std::string& what) {
  if (flipped > 0) {
    note(
        fmt::format("warning: {} faces turned inside out: the {} exceeds the local radius of curvature, "
                    "so the solid intersects itself there; use a smaller value or a smoother surface",
                    flipped, what));
  }
}

}  // namespace

void add_support_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "support", "Support object (solid for 3D printing) for a knitted sample of a surface (seed 2.C)");
  struct Opts : Common {
    double offset = 1.0, thickness = 0.0, base_height = 10.0, margin = 5.0;
    std::string base = "projected";
  };
  auto o = std::make_shared<Opts>();
  add_common(*cmd, *o, "Output solid (.stl for printing; .ply/.obj/.off)");
  cmd->add_option("--offset", o->offset, "Inward offset of the surface: the fabric thickness (mm, default 1)")
      ->check(number_in(0, 1e6));
  cmd->add_option("--thickness", o->thickness,
                  "Make a hollow shell of this thickness (mm) instead of a solid with a base")
      ->check(number_in(0, 1e6));
  cmd->add_option("--base-height", o->base_height,
                  "Height of the base below the lowest point of the surface (mm, default 10)")
      ->check(positive_number())
      ->check(number_in(0, 1e6));
  cmd->add_option("--base", o->base, "Base: 'projected' (boundary projected down) or 'rectangle' (seed)")
      ->check(CLI::IsMember({"projected", "rectangle"}));
  cmd->add_option("--margin", o->margin, "Margin of the rectangle base around the surface (mm, default 5)")
      ->check(number_in(0, 1e6));
  cmd->callback([=, &action] {
    action = [=]() -> int {
      check_common(*o);
      std::string description;
      const TriMesh surface = load_surface_or_shape(o->input, o->units, o->edge, description);
      SupportOptions so;
      so.offset = o->offset;
      so.shell_thickness = o->thickness;
      so.base_height = o->base_height;
      so.base = o->base == "rectangle" ? SupportBase::Rectangle : SupportBase::Projected;
      so.base_margin = o->margin;
      const SupportObject s = support_object(surface, so);
      if (s.reoriented)
        note("the surface's normals pointed down: reoriented so that the support lies below it");
      warn_flips(s.flipped_faces, o->thickness > 0.0 ? "offset or shell thickness" : "offset");
      write_mesh(o->output, s.solid);
      note(fmt::format("support of {}: {} -> {}", description, size_text(s.solid), o->output));
      return 0;
    };
  });
}

void add_close_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "close", "Close a mesh into a watertight surface by alpha wrapping (the sock from a foot, seed 2.C.3)");
  struct Opts : Common {
    double alpha = 0.0, offset = 0.0, max_faces = 2e6;
    bool no_cap = false;
  };
  auto o = std::make_shared<Opts>();
  add_common(*cmd, *o, "Output mesh (.stl, .ply, .obj, .off)");
  cmd->add_option("--alpha", o->alpha,
                  "Radius of the wrapping ball (mm): gaps narrower than about twice this are bridged "
                  "(default: bounding-box diagonal / 20)")
      ->check(number_in(0, 1e6));
  cmd->add_option("--offset", o->offset, "Distance of the result from the input (mm, default alpha / 30)")
      ->check(number_in(0, 1e6));
  cmd->add_flag(
      "--no-cap", o->no_cap,
      "Do not close the input's holes with planar caps first (an open input then gives a thin shell)");
  cmd->add_option("--max-faces", o->max_faces,
                  "Refuse when the result is estimated above this many triangles (default 2 million, ~5 min)")
      ->check(positive_number());
  cmd->callback([=, &action] {
    action = [=]() -> int {
      check_common(*o);
      std::string description;
      const TriMesh input = load_surface_or_shape(o->input, o->units, o->edge, description);
      AlphaCloseOptions ao;
      ao.alpha = o->alpha;
      ao.offset = o->offset;
      ao.cap_holes = !o->no_cap;
      ao.max_faces = o->max_faces;
      note("wrapping ...");
      const AlphaCloseResult r = alpha_close(input, ao);
      write_mesh(o->output, r.mesh);
      note(fmt::format("closed {} (alpha {:.3g} mm, offset {:.3g} mm, holes capped: {}): {} -> {}",
                       description, r.alpha, r.offset, r.capped_holes, size_text(r.mesh), o->output));
      return 0;
    };
  });
}

void add_thicken_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand("thicken", "Thicken an open surface into a watertight solid (seed 2.C.2)");
  struct Opts : Common {
    double thickness = 0.0;
    std::string side = "both";
  };
  auto o = std::make_shared<Opts>();
  add_common(*cmd, *o, "Output solid (.stl, .ply, .obj, .off)");
  cmd->add_option("--thickness", o->thickness, "Thickness (mm)")
      ->required()
      ->check(positive_number())
      ->check(number_in(0, 1e6));
  cmd->add_option("--side", o->side,
                  "Where the material goes: 'both' (centred), 'outside' (along the normals), 'inside'")
      ->check(CLI::IsMember({"both", "outside", "inside"}));
  cmd->callback([=, &action] {
    action = [=]() -> int {
      check_common(*o);
      std::string description;
      const TriMesh surface = load_surface_or_shape(o->input, o->units, o->edge, description);
      ThickenOptions to;
      to.thickness = o->thickness;
      to.side = o->side == "outside"  ? ThickenSide::Outside
                : o->side == "inside" ? ThickenSide::Inside
                                      : ThickenSide::Both;
      const ThickenResult r = thicken_surface(surface, to);
      warn_flips(r.flipped_faces, "thickness");
      write_mesh(o->output, r.solid);
      note(fmt::format("thickened {}: {} -> {}", description, size_text(r.solid), o->output));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
