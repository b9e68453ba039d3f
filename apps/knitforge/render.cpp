// knitforge render: stitch mesh / knitting map / triangle mesh -> picture or
// 3D file: yarn tubes or the coloured stitch mesh as .glb or .obj, a
// technical-drawing .svg (seed Alg. 1.2) or a shaded .png preview.
#include <fmt/core.h>

#include <algorithm>
#include <sstream>

#include "cli_common.h"
#include "knitforge/convert/map_to_stitch_mesh.h"
#include "knitforge/convert/stitch_mesh_to_yarn.h"
#include "knitforge/geometry/mesh_measures.h"
#include "knitforge/io/colours.h"
#include "knitforge/io/gltf.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/png_image.h"
#include "knitforge/render/camera.h"
#include "knitforge/render/raster_preview.h"
#include "knitforge/render/vector_drawing.h"
#include "knitforge/render/yarn_tubes.h"
#include "knitforge/util/atomic_file.h"

namespace knitforge::cli {

namespace {

RenderColour to_render(Rgb c) { return {c.r, c.g, c.b}; }

Vec3 parse_vec3(const std::string& key, const std::string& text) {
  std::stringstream ss(text);
  std::string part;
  std::vector<double> v;
  while (std::getline(ss, part, ',')) {
    try {
      size_t used = 0;
      v.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw InvalidInput(fmt::format("--camera: '{}={}' is not three numbers x,y,z", key, text));
    }
  }
  if (v.size() != 3)
    throw InvalidInput(fmt::format("--camera: '{}={}' is not three numbers x,y,z", key, text));
  return {v[0], v[1], v[2]};
}

// "eye=x,y,z:target=x,y,z:up=x,y,z", each part optional.
struct CameraSpec {
  std::optional<Vec3> eye, target, up;
};
CameraSpec parse_camera(const std::string& text) {
  CameraSpec c;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos) {
      throw InvalidInput(fmt::format("--camera: '{}' should be key=x,y,z with key eye, target or up", part));
    }
    const std::string key = part.substr(0, eq), value = part.substr(eq + 1);
    if (key == "eye")
      c.eye = parse_vec3(key, value);
    else if (key == "target")
      c.target = parse_vec3(key, value);
    else if (key == "up")
      c.up = parse_vec3(key, value);
    else
      throw InvalidInput(fmt::format("--camera: unknown key '{}'; use eye, target and up", key));
  }
  return c;
}

std::pair<int, int> parse_pixels(const std::string& text) {
  const auto x = text.find('x');
  int w = 0, h = 0;
  try {
    if (x == std::string::npos) throw std::invalid_argument(text);
    size_t a = 0, b = 0;
    w = std::stoi(text.substr(0, x), &a);
    h = std::stoi(text.substr(x + 1), &b);
    if (a != x || b != text.size() - x - 1) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw InvalidInput(fmt::format("--size: '{}' should be WIDTHxHEIGHT in pixels, e.g. 800x600", text));
  }
  if (w < 1 || h < 1 || w > 16384 || h > 16384) {
    throw InvalidInput(fmt::format("--size: {}x{} px must be within 1..16384 in each direction", w, h));
  }
  return {w, h};
}

// All meshes merged into one triangle mesh with per-vertex colours (OBJ).
void write_obj_meshes(const std::string& path, const std::vector<RenderMesh>& meshes) {
  TriMesh all;
  MeshWriteOptions opt;
  for (const RenderMesh& m : meshes) {
    validate_render_mesh(m);
    const int base = all.num_vertices();
    if (!m.face_colours.empty()) {  // OBJ has vertex colours only: one vertex per face corner
      for (size_t f = 0; f < m.mesh.faces.size(); ++f) {
        const int b = all.num_vertices();
        for (int k = 0; k < 3; ++k) {
          all.vertices.push_back(
              m.mesh.vertices[static_cast<size_t>(m.mesh.faces[f][static_cast<size_t>(k)])]);
          const RenderColour& c = m.face_colours[f];
          opt.vertex_colours.push_back({c[0], c[1], c[2]});
        }
        all.faces.push_back({b, b + 1, b + 2});
      }
      continue;
    }
    for (size_t v = 0; v < m.mesh.vertices.size(); ++v) {
      all.vertices.push_back(m.mesh.vertices[v]);
      const RenderColour& c = m.vertex_colours.empty() ? m.colour : m.vertex_colours[v];
      opt.vertex_colours.push_back({c[0], c[1], c[2]});
    }
    for (const auto& f : m.mesh.faces) all.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  }
  write_mesh(path, all, opt);
}

}  // namespace

void add_render_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "render",
      "Stitch mesh (.ply), knitting map (.csv) or triangle mesh -> yarn tubes or coloured mesh as .glb/.obj, "
      "a vector drawing (.svg) or a shaded preview (.png)");
  /// Above this many stitches `--detail auto` renders yarn at preview detail.
  constexpr int kFullDetailStitches = 20000;
  struct Opts {
    std::string input, output, stitch = "3.5x2.8", camera, size = "800x600", units = "mm", detail = "auto";
    bool yarn = false, mesh = false, ortho = false, edges = false, open_ends = false;
    double fov = 30.0, max_stitches = kDefaultMaxStitches, max_triangles = 5e7;
    TubeOptions tube;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("input", o->input,
                  "Stitch mesh (.ply), knitting map (.csv) or triangle mesh (.obj/.ply/.off/.stl)")
      ->required();
  cmd->add_option("-o,--output", o->output, "Output: .glb, .obj, .svg or .png")->required();
  add_stitch_option(*cmd, o->stitch);
  auto* yarn_flag =
      cmd->add_flag("--yarn", o->yarn, "Render the yarn model as tubes (default for stitch inputs)");
  auto* mesh_flag =
      cmd->add_flag("--mesh", o->mesh, "Render the stitch mesh coloured by course (shaping marked)");
  yarn_flag->excludes(mesh_flag);
  mesh_flag->excludes(yarn_flag);
  cmd->add_option("--camera", o->camera,
                  "Camera 'eye=x,y,z:target=x,y,z:up=x,y,z' in mm, parts optional (default: frame the model "
                  "from the front, slightly from the side and below)");
  cmd->add_flag("--ortho", o->ortho, "Orthographic instead of perspective projection");
  cmd->add_option("--fov", o->fov, "Perspective vertical field of view in degrees (default 30)")
      ->check(number_in(1.0, 170.0));
  cmd->add_option("--size", o->size,
                  "Picture size WIDTHxHEIGHT in pixels (.png; .svg uses the width and aspect)");
  cmd->add_flag("--edges", o->edges, "PNG: draw stitch outlines (--mesh) or triangle edges");
  cmd->add_option("--units", o->units, "Units of a plain triangle-mesh input: mm, cm or m (default mm)");
  cmd->add_option("--radius", o->tube.radius, "Tube (yarn) radius in mm (0 = 0.12 x stitch width)")
      ->check(non_negative_number());
  cmd->add_option("--plies", o->tube.plies, "Plies per yarn (sides of the twisted prism, default 6)")
      ->check(number_in(1, 64));
  cmd->add_option("--ply-vertices", o->tube.vertices_per_ply, "Cross-section vertices per ply (default 2)")
      ->check(number_in(1, 32));
  cmd->add_option("--ply-depth", o->tube.ply_depth, "Ply relief in [0, 1] (default 0.3)")
      ->check(number_in(0.0, 1.0));
  cmd->add_option("--twist", o->tube.twist_per_mm, "Ply twist in turns per mm (default 0.15)");
  auto* ply_vertices_opt = cmd->get_option("--ply-vertices");
  auto* ring_spacing_opt = cmd->add_option("--ring-spacing", o->tube.ring_spacing,
                                           "Distance between tube cross-sections in mm (0 = radius)")
                               ->check(non_negative_number());
  cmd->add_option("--detail", o->detail,
                  "Yarn tube detail: full (plies with relief, a cross-section every radius), preview (plain "
                  "twisted prism, a cross-section every mm) or auto (full up to " +
                      std::to_string(kFullDetailStitches) + " stitches, preview beyond; default)")
      ->check(CLI::IsMember({"auto", "full", "preview"}));
  cmd->add_flag("--open-ends", o->open_ends, "Leave the yarn ends open (no caps)");
  add_max_stitches_option(*cmd, o->max_stitches);
  cmd->add_option("--max-triangles", o->max_triangles,
                  "Refuse yarn tubes estimated above this many triangles (default 50 million, ~2.5 GB)")
      ->check(positive_number());
  cmd->callback([=, &action] {
    action = [=]() -> int {
      const KnitParams params = parse_stitch_size(o->stitch);
      check_output_file("-o", o->output, {".glb", ".obj", ".svg", ".png"}, {o->input});
      const std::string ext = extension(o->output);
      const auto [width, height] = parse_pixels(o->size);
      const CameraSpec spec = parse_camera(o->camera);

      // The scene.
      std::vector<RenderMesh> scene;
      bool written = false;  // the .glb of yarn tubes is streamed while the scene is made
      const std::string in_ext = extension(o->input);
      const bool stitch_input = in_ext == ".csv" || (in_ext == ".ply" && is_stitch_mesh_ply(o->input));
      if (stitch_input) {
        const StitchInput in = load_stitch_input(o->input);
        const double stitches = in.is_map ? static_cast<double>(in.map.num_stitches()) : in.mesh.num_stitches();
        check_work({fmt::format("rendering {}", o->input), stitches, "stitches", o->max_stitches, 0.0,
                    "raise the limit with --max-stitches"});
        const StitchMesh mesh = in.is_map ? map_to_stitch_mesh(in.map, params) : in.mesh;
        if (o->mesh) {
          StitchColourOptions colours;
          colours.course_colours = {to_render(map_cell_background(CellType::Knit, 1)),
                                    to_render(map_cell_background(CellType::Knit, -1))};
          for (int t = 0; t < kNumStitchTypes; ++t) {
            colours.type_colours[static_cast<size_t>(t)] =
                to_render(stitch_type_colour(static_cast<StitchType>(t)));
          }
          scene.push_back(stitch_mesh_render_mesh(mesh, colours));
          note(fmt::format("stitch mesh: {} stitches", mesh.num_stitches()));
        } else {
          TubeOptions tube = o->tube;
          tube.capped = !o->open_ends;
          // Preview detail: about 5x fewer vertices (a 100k-stitch .glb of
          // 0.4 GB instead of 1.7 GB); explicit --ply-vertices/--ring-spacing win.
          const bool preview =
              o->detail == "preview" || (o->detail == "auto" && mesh.num_stitches() > kFullDetailStitches);
          if (preview) {
            if (ply_vertices_opt->count() == 0) tube.vertices_per_ply = 1;
            if (ring_spacing_opt->count() == 0) tube.ring_spacing = 1.0;
            if (o->detail == "auto") {
              note(fmt::format("{} stitches: preview tube detail (--detail full for plies with relief)",
                               mesh.num_stitches()));
            }
          }
          YarnOptions yarn_options;
          yarn_options.yarn_radius = tube.radius;  // the loops' offsets match the tubes
          const YarnModel yarn = stitch_mesh_to_yarn(mesh, params, yarn_options);
          {
            // Tube triangles: a ring of plies x vertices per ply every ring spacing along the yarn.
            double length = 0.0;
            for (const Yarn& y : yarn.yarns)
              for (size_t k = 1; k < y.points.size(); ++k) length += (y.points[k] - y.points[k - 1]).norm();
            const double radius = tube.radius > 0.0 ? tube.radius : 0.12 * params.stitch_width;
            const double spacing = tube.ring_spacing > 0.0 ? tube.ring_spacing : radius;
            const double triangles = 2.0 * (length / spacing + 1.0) * tube.plies * tube.vertices_per_ply;
            check_work({fmt::format("yarn tubes of {:.4g} m of yarn every {:.3g} mm", length / 1000.0, spacing),
                        triangles, "triangles", o->max_triangles, 50.0,
                        "use a larger --ring-spacing, --detail preview, or raise the limit with --max-triangles"});
          }
          std::vector<RenderColour> colours;
          for (const Yarn& y : yarn.yarns) {
            colours.push_back(
                to_render(y.id <= 0 ? stitch_type_colour(StitchType::Knit) : yarn_colour(y.id)));
          }
          size_t nv = 0, nf = 0;
          if (ext == ".glb") {  // streamed straight to the file, no meshes in memory
            const YarnGlbSummary s = write_yarn_glb(o->output, yarn, params, tube, colours);
            written = true;
            nv = s.vertices;
            nf = s.triangles;
          } else {
            scene = yarn_tubes(yarn, params, tube, colours);
            for (const RenderMesh& m : scene) {
              nv += m.mesh.vertices.size();
              nf += m.mesh.faces.size();
            }
          }
          note(fmt::format("{} yarn(s) for {} stitches: {} tube vertices, {} triangles", yarn.yarns.size(),
                           mesh.num_stitches(), nv, nf));
        }
      } else {
        if (o->yarn) {
          throw InvalidInput(
              fmt::format("{}: --yarn needs a stitch mesh (.ply with stitch properties) or a "
                          "knitting map (.csv); this is a plain triangle mesh",
                          o->input));
        }
        RenderMesh m;
        m.name = "mesh";
        m.mesh = load_surface(o->input, o->units);
        m.normals = vertex_normals(m.mesh);
        m.colour = to_render(stitch_type_colour(StitchType::Knit));
        scene.push_back(std::move(m));
      }

      if (ext == ".glb") {
        if (!written) write_glb(o->output, scene);
      } else if (ext == ".obj") {
        write_obj_meshes(o->output, scene);
      } else {
        const double aspect = static_cast<double>(width) / height;
        std::vector<Vec3> points;
        for (const RenderMesh& m : scene)
          points.insert(points.end(), m.mesh.vertices.begin(), m.mesh.vertices.end());
        // frame the model, then apply the parts of --camera the user gave
        Camera camera =
            frame_points(points, aspect, o->ortho, Vec3(0.25, -0.35, 1.0), spec.up.value_or(Vec3::UnitY()));
        if (spec.target) {
          camera.eye += *spec.target - camera.target;
          camera.target = *spec.target;
        }
        if (spec.eye) camera.eye = *spec.eye;
        camera.fov_y_degrees = o->fov;
        if (ext == ".png") {
          RasterOptions ro;
          ro.width = width;
          ro.height = height;
          ro.edges = o->edges;
          write_png(o->output, rasterize(scene, camera, ro));
        } else {
          const VectorDrawing d = vector_drawing(scene, camera);
          SvgOptions so;
          so.width = width;
          so.background = true;
          const std::string svg = vector_drawing_svg(d, so);
          write_file_atomically(o->output, [&](std::ostream& os) { os << svg; });
          note(fmt::format("{} contour segments, {} visible edges ({} hidden), {} regions",
                           d.contour_segments, d.edges.size(), d.hidden_edges, d.regions.size()));
        }
      }
      note(fmt::format("-> {}", o->output));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
