#include "knitforge/report/report_html.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <ostream>
#include <set>

#include <fmt/format.h>

#include "knitforge/core/knitting_map.h"
#include "knitforge/core/stitch_mesh.h"
#include "knitforge/geometry/tri_mesh.h"
#include "knitforge/io/io_detail.h"
#include "knitforge/io/knitting_map_csv.h"
#include "knitforge/io/mesh_io.h"
#include "knitforge/io/ply_format.h"
#include "knitforge/io/polyline_obj.h"
#include "knitforge/io/read_gltf_animation.h"
#include "knitforge/io/stitch_mesh_ply.h"
#include "knitforge/machine/knitout_parse.h"
#include "knitforge/machine/knitout_simulate.h"
#include "knitforge/machine/machine_profile.h"
#include "knitforge/report/simulation_json.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

// The viewer bundle, generated at build time from web/ (CMakeLists.txt,
// web/embed_bundle.cmake): raw string chunks to be concatenated.
namespace knitforge::report_detail {
extern const char* const kViewerScriptChunks[];
extern const std::size_t kViewerScriptChunkCount;
}  // namespace knitforge::report_detail

namespace knitforge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// Face properties of stitch_mesh.ply that are stitch attributes, not scalars.
const std::set<std::string, std::less<>> kStitchFaceProperties = {
    "vertex_indices", "vertex_index", "type", "direction", "course", "wale",
    "yarn",           "roles",        "red",  "green",     "blue",   "alpha"};

class Quantizer {
 public:
  Quantizer(double quantum, std::string file) : quantum_(quantum), file_(std::move(file)) {}
  int64_t operator()(double x) const {
    const double q = x / quantum_;
    if (!std::isfinite(q) || std::abs(q) > 1e15) {
      throw InvalidInput(fmt::format("{}: coordinate {} is too large for the report's resolution of {} mm",
                                     file_, x, quantum_));
    }
    return static_cast<int64_t>(std::llround(q));
  }
  json positions(const std::vector<Vec3>& pts) const {
    json a = json::array();
    a.get_ref<json::array_t&>().reserve(pts.size() * 3);
    for (const Vec3& p : pts) {
      a.push_back((*this)(p.x()));
      a.push_back((*this)(p.y()));
      a.push_back((*this)(p.z()));
    }
    return a;
  }

 private:
  double quantum_;
  std::string file_;
};

/// Rounds the values of a scalar field to 5 significant digits of its
/// largest magnitude (NaN and infinities become null).
json rounded_field(const std::vector<double>& v) {
  double maxabs = 0.0;
  for (double x : v) {
    if (std::isfinite(x)) maxabs = std::max(maxabs, std::abs(x));
  }
  const double step = maxabs > 0.0 ? std::pow(10.0, std::floor(std::log10(maxabs)) - 4.0) : 1.0;
  json a = json::array();
  a.get_ref<json::array_t&>().reserve(v.size());
  for (double x : v) {
    if (!std::isfinite(x)) {
      a.push_back(nullptr);
    } else {
      const double r = std::round(x / step) * step;
      // Print with few digits: go through the shortest decimal of the rounded value.
      a.push_back(std::stod(fmt::format("{:.{}g}", r, 6)));
    }
  }
  return a;
}

json tri_mesh_json(const TriMesh& m, const Quantizer& q) {
  json out = json::object();
  out["positions"] = q.positions(m.vertices);
  json tri = json::array();
  tri.get_ref<json::array_t&>().reserve(m.faces.size() * 3);
  for (const auto& f : m.faces) {
    for (int k = 0; k < 3; ++k) tri.push_back(f[k]);
  }
  out["triangles"] = std::move(tri);
  return out;
}

/// The scalar face properties of a stitch-mesh PLY that are not stitch
/// attributes (e.g. shape_error, distortion), per stitch in file order.
std::map<std::string, std::vector<double>> stitch_scalar_properties(const std::string& path) {
  using namespace ply_detail;
  const std::string data = io_detail::load_file(path);
  const PlyHeader header = read_ply_header(path, data);
  const int face = header.find("face");
  std::map<std::string, std::vector<double>> fields;
  if (face < 0) return fields;
  std::vector<std::pair<int, std::string>> wanted;
  const PlyElement& el = header.elements[face];
  for (int i = 0; i < static_cast<int>(el.properties.size()); ++i) {
    const PlyProperty& p = el.properties[i];
    if (p.is_list || kStitchFaceProperties.count(p.name) > 0) continue;
    wanted.emplace_back(i, p.name);
    fields[p.name].reserve(static_cast<size_t>(el.count));
  }
  if (wanted.empty()) return fields;
  read_ply_body(path, data, header, [&](int element, const PlyRecord& rec) {
    if (element != face) return;
    for (const auto& [i, name] : wanted) fields[name].push_back(rec.values[i]);
  });
  return fields;
}

/// True when the PLY file's faces carry a `type` property (a stitch mesh).
bool ply_has_stitch_types(const std::string& path) {
  const std::string data = io_detail::load_file(path);
  const ply_detail::PlyHeader header = ply_detail::read_ply_header(path, data);
  const int face = header.find("face");
  return face >= 0 && header.elements[face].find("type") >= 0;
}

json stitch_mesh_json(const std::string& path, const Quantizer& q) {
  const StitchMesh mesh = read_stitch_mesh_ply(path);
  json out = json::object();
  out["positions"] = q.positions(mesh.vertices);
  json corners = json::array(), type = json::array(), dir = json::array(), course = json::array(),
       wale = json::array(), yarn = json::array();
  bool any_yarn = false;
  for (const Stitch& s : mesh.stitches) {
    for (int k = 0; k < 4; ++k) corners.push_back(k < s.corners() ? s.v[k] : -1);
    type.push_back(static_cast<int>(s.type));
    dir.push_back(static_cast<int>(s.direction));
    course.push_back(s.course);
    wale.push_back(s.wale);
    yarn.push_back(s.yarn);
    any_yarn = any_yarn || s.yarn != 0;
  }
  out["corners"] = std::move(corners);
  out["type"] = std::move(type);
  out["direction"] = std::move(dir);
  out["course"] = std::move(course);
  out["wale"] = std::move(wale);
  if (any_yarn) out["yarn"] = std::move(yarn);
  json scalars = json::object();
  for (const auto& [name, values] : stitch_scalar_properties(path)) {
    if (values.size() == mesh.stitches.size()) scalars[name] = rounded_field(values);
  }
  out["scalars"] = std::move(scalars);
  return out;
}

json map_json(const KnittingMap& map) {
  static constexpr char kCodes[] = "KLRIDC.";
  json out = json::object();
  out["rows"] = map.rows;
  out["cols"] = map.cols;
  std::string cells;
  cells.reserve(map.cells.size());
  for (CellType c : map.cells) cells.push_back(kCodes[std::min<int>(static_cast<int>(c), 6)]);
  out["cells"] = std::move(cells);
  json dir = json::array();
  for (int8_t d : map.direction) dir.push_back(static_cast<int>(d));
  out["direction"] = std::move(dir);
  if (!map.yarn.empty() && std::any_of(map.yarn.begin(), map.yarn.end(), [](int y) { return y != 0; })) {
    out["yarn"] = map.yarn;
  }
  return out;
}

/// The polylines, thinned to every k-th point (and the last) when they have
/// more than max_points points in total; a note in `notes` says so.
json polylines_json(std::vector<NamedPolyline> lines, const Quantizer& q, int64_t max_points,
                    const std::string& file, json& notes) {
  int64_t total = 0;
  for (const NamedPolyline& l : lines) total += static_cast<int64_t>(l.points.size());
  if (max_points > 0 && total > max_points) {
    const int64_t k = (total + max_points - 1) / max_points;
    int64_t kept = 0;
    for (NamedPolyline& l : lines) {
      std::vector<Vec3> thin;
      const int64_t n = static_cast<int64_t>(l.points.size());
      for (int64_t i = 0; i < n; i += k) thin.push_back(l.points[i]);
      if (n > 0 && (n - 1) % k != 0) thin.push_back(l.points[n - 1]);
      kept += static_cast<int64_t>(thin.size());
      l.points = std::move(thin);
    }
    notes.push_back(fmt::format("{}: {} points; the page draws one point in {} ({} points) to open quickly",
                                file, total, k, kept));
  }
  json names = json::array(), polys = json::array();
  for (const NamedPolyline& l : lines) {
    names.push_back(l.name);
    polys.push_back(q.positions(l.points));
  }
  return json{{"names", std::move(names)}, {"polylines", std::move(polys)}};
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

json knitout_json(const std::string& path, bool simulate) {
  const KnitoutFile file = read_knitout(path);
  json out = json::object();
  out["lines"] = file.num_lines;
  json headers = json::object();
  for (const KnitoutHeader& h : file.headers) headers[h.key] = h.value;
  out["headers"] = std::move(headers);
  out["carriers"] = file.carrier_names;
  std::map<std::string, int> ops;
  int comments = 0;
  for (const KnitoutInstruction& in : file.instructions) {
    if (in.op == KnitoutOp::Comment) {
      ++comments;
    } else {
      ++ops[std::string(in.op == KnitoutOp::Extension ? std::string_view("x- extensions") : name(in.op))];
    }
  }
  out["operations"] = ops;
  out["comment_lines"] = comments;
  int perr = 0, pwarn = 0;
  for (const KnitoutDiagnostic& d : file.diagnostics) (d.severity == Severity::Error ? perr : pwarn)++;
  out["parse_errors"] = perr;
  out["parse_warnings"] = pwarn;
  if (!simulate) return out;

  const std::string* machine = file.header("Machine");
  const MachineProfile* profile = nullptr;
  if (machine != nullptr) {
    for (const std::string& n : machine_profile_names()) {
      const MachineProfile& p = machine_profile(n);
      if (lower(p.knitout_machine) == lower(*machine) || lower(p.name) == lower(*machine)) {
        profile = &p;
        break;
      }
    }
  }
  if (profile == nullptr) {
    out["simulation"] = machine == nullptr ? "not run: the program has no ;;Machine: header"
                                           : "not run: no machine profile for ;;Machine: " + *machine;
    return out;
  }
  // The verdict as `simulate --json` gives it, with the first 20 findings.
  json s = simulation_json(simulate_knitout(file, *profile), 20);
  s["machine"] = profile->display_name;
  out["simulation"] = std::move(s);
  return out;
}

json read_metrics(const std::string& path) {
  const std::string text = io_detail::load_file(path);
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw IOError(
        fmt::format("{}: byte {}: not valid JSON ({}); fix or remove the file", path, e.byte, e.what()));
  }
}

/// A per-frame field of a cloth run (cloth.json "fields"), shown on the
/// garment: its key, label, unit, element ("triangle" or "vertex") and the
/// key of its measure's description in cloth.json's "result".
struct FrameFieldKind {
  const char* key;
  const char* label;
  const char* unit;
  const char* per;
  const char* measure;
};
constexpr FrameFieldKind kFrameFields[] = {{"stress_kpa", "stress", "kPa", "triangle", "stress_measure"},
                                           {"sliding_mm", "sliding", "mm", "vertex", "sliding_measure"}};

/// One field's values per frame (NaN for null), as cloth.json holds them.
struct FrameField {
  const FrameFieldKind* kind;
  std::vector<std::vector<double>> frames;
};

/// The per-frame fields of cloth.json for a garment layer of `triangles`
/// triangles and `vertices` vertices animated over `frames` frames; a field
/// whose sizes disagree is left out with a note.
std::vector<FrameField> cloth_fields(const std::string& path, size_t frames, size_t triangles,
                                     size_t vertices, json& result, json& notes) {
  const json j = read_metrics(path);
  std::vector<FrameField> out;
  const json* fields = j.is_object() && j.contains("fields") ? &j["fields"] : nullptr;
  if (fields == nullptr || !fields->is_array() || fields->size() != frames) {
    notes.push_back(
        fmt::format("cloth.json: {} per-frame fields for the {} frames of animation.glb: the garment "
                    "is not coloured",
                    fields != nullptr && fields->is_array() ? fields->size() : 0, frames));
    return out;
  }
  if (j.contains("result") && j["result"].is_object()) result = j["result"];
  for (const FrameFieldKind& kind : kFrameFields) {
    const size_t count = std::string_view(kind.per) == "triangle" ? triangles : vertices;
    FrameField f{&kind, {}};
    for (const json& frame : *fields) {
      const json* v = frame.is_object() && frame.contains(kind.key) ? &frame[kind.key] : nullptr;
      if (v == nullptr || !v->is_array() || v->size() != count) break;
      std::vector<double>& values = f.frames.emplace_back();
      values.reserve(count);
      for (const json& x : *v) values.push_back(x.is_number() ? x.get<double>() : std::nan(""));
    }
    if (f.frames.size() == frames) {
      out.push_back(std::move(f));
    } else {
      notes.push_back(fmt::format("cloth.json: {} is not one value per {} ({}) in every frame: not shown",
                                  kind.key, kind.per, count));
    }
  }
  return out;
}

/// A field's kept frames as integers in units of `step`, a power of ten
/// giving at most 1,000 levels below the largest value over all frames
/// (not only those kept), so the colours of every frame share one scale.
json quantised_field(const FrameField& f, const std::vector<size_t>& keep, const json& result) {
  double lo = 0.0, hi = 0.0;
  for (const std::vector<double>& frame : f.frames) {
    for (double x : frame) {
      if (!std::isfinite(x)) continue;
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  const double top = std::max(hi, -lo);
  const double step = top > 0.0 ? std::pow(10.0, std::ceil(std::log10(top)) - 3.0) : 1.0;
  json frames = json::array();
  for (size_t k : keep) {
    json a = json::array();
    a.get_ref<json::array_t&>().reserve(f.frames[k].size());
    for (double x : f.frames[k]) {
      if (std::isfinite(x))
        a.push_back(static_cast<int64_t>(std::llround(x / step)));
      else
        a.push_back(nullptr);
    }
    frames.push_back(std::move(a));
  }
  json out = {{"label", f.kind->label}, {"unit", f.kind->unit}, {"per", f.kind->per}, {"step", step}};
  out["range"] = rounded_field({lo, hi});
  out["frames"] = std::move(frames);
  if (result.contains(f.kind->measure) && result[f.kind->measure].is_string())
    out["measure"] = result[f.kind->measure];
  return out;
}

/// The frames of animation.glb (what `cloth` writes: meshes "garment" and
/// "body") for the layers they move: "relaxed" (the garment) and "target"
/// (the body), each only when the layer has as many vertices; and, from
/// cloth.json next to it, the garment's per-frame fields (stress per
/// triangle, sliding per vertex) when it is a plain mesh of their sizes.
/// Beyond max_values coordinates and field values in all, every layer and
/// field keeps the same frames (every k-th, and the last), with a note.
json animation_json(const std::string& path, const std::string& cloth_path, const json& data,
                    const Quantizer& q, int64_t max_values, json& files, json& notes) {
  struct Layer {
    const char* layer;
    GltfAnimatedMesh mesh;
  };
  std::vector<Layer> moving;
  for (const auto& [mesh_name, layer] : {std::pair{"garment", "relaxed"}, std::pair{"body", "target"}}) {
    if (!data.contains(layer) || !data[layer].contains("positions")) continue;
    GltfReadOptions o;
    o.mesh_name = mesh_name;
    GltfAnimatedMesh m;
    try {
      m = read_gltf_animation(path, o);
    } catch (const InvalidInput&) {
      continue;  // no such mesh in the file
    }
    const size_t nv = data[layer]["positions"].size() / 3;
    if (static_cast<size_t>(m.num_vertices) != nv || m.channels.empty()) {
      notes.push_back(fmt::format("animation.glb: mesh '{}' has {} vertices, the {} layer {}: not animated",
                                  mesh_name, m.num_vertices, layer, nv));
      continue;
    }
    moving.push_back({layer, std::move(m)});
  }
  if (moving.empty()) return json();
  const std::vector<double> times = moving.front().mesh.channels.front().times;
  const size_t n = times.size();

  std::vector<FrameField> fields;
  json result = json::object();
  std::error_code ec;
  if (std::string_view(moving.front().layer) == "relaxed" && data["relaxed"].value("kind", "") == "mesh" &&
      fs::is_regular_file(cloth_path, ec)) {
    const json& relaxed = data["relaxed"];
    files.push_back(
        json{{"name", "cloth.json"}, {"bytes", static_cast<uint64_t>(fs::file_size(cloth_path, ec))}});
    fields = cloth_fields(cloth_path, n, relaxed["triangles"].size() / 3, relaxed["positions"].size() / 3,
                          result, notes);
  }

  size_t per_frame = 0;
  for (const Layer& l : moving) per_frame += 3 * static_cast<size_t>(l.mesh.num_vertices);
  for (const FrameField& f : fields) per_frame += f.frames.front().size();
  size_t step = 1;
  if (max_values > 0) {
    while (per_frame * ((n + step - 1) / step) > static_cast<size_t>(max_values) && step < n) ++step;
  }
  if (step > 1) {
    notes.push_back(
        fmt::format("animation.glb: {} frames shown every {} (the page's size: at most {} coordinates "
                    "and field values)",
                    n, step, max_values));
  }
  std::vector<size_t> keep;
  for (size_t k = 0; k < n; k += step) keep.push_back(k + step >= n ? n - 1 : k);  // always the last frame
  json keep_times = json::array();
  for (size_t f : keep) keep_times.push_back(times[f]);

  json layers = json::object();
  for (const Layer& l : moving) {
    json frames = json::array();
    for (size_t f : keep) frames.push_back(q.positions(gltf_positions_at(l.mesh, times[f])));
    layers[l.layer] = {{"times", keep_times}, {"frames", std::move(frames)}};
  }
  if (!fields.empty()) {
    json shown = json::object();
    for (const FrameField& f : fields) shown[f.kind->key] = quantised_field(f, keep, result);
    layers["relaxed"]["fields"] = std::move(shown);
  }
  return json{{"layers", std::move(layers)}};
}

}  // namespace

const std::vector<std::string>& report_input_files() {
  static const std::vector<std::string> files = {"report.json", "target.ply",    "stitch_mesh.ply",
                                                 "relaxed.ply", "predicted.ply", "knitting_map.csv",
                                                 "wales.obj",   "yarn.obj",      "knitout.k"};
  return files;
}

json report_data(const std::string& outdir, const ReportHtmlOptions& options) {
  if (!(options.quantum_mm > 0.0) || !std::isfinite(options.quantum_mm)) {
    throw InvalidInput(fmt::format("report: the coordinate resolution must be a positive length, not {} mm",
                                   options.quantum_mm));
  }
  std::error_code ec;
  if (!fs::is_directory(outdir, ec)) {
    throw IOError(fmt::format("{}: not a directory; give the output directory of a design command", outdir));
  }
  json data = json::object();
  data["format"] = "knitforge-report";
  data["version"] = 1;
  std::string title = options.title;
  if (title.empty()) {
    fs::path p = fs::path(outdir).lexically_normal();
    if (!p.has_filename()) p = p.parent_path();
    title = fs::absolute(p, ec).filename().string();
    if (title.empty()) title = outdir;
  }
  data["title"] = title;
  data["scale"] = options.quantum_mm;

  json files = json::array(), notes = json::array();
  std::vector<std::string> missing;
  auto has = [&](const std::string& name, std::string& path) {
    path = (fs::path(outdir) / name).string();
    std::error_code e;
    if (!fs::is_regular_file(path, e)) {
      missing.push_back(name);
      return false;
    }
    files.push_back(json{{"name", name}, {"bytes", static_cast<uint64_t>(fs::file_size(path, e))}});
    return true;
  };
  std::string path;
  if (has("report.json", path)) data["metrics"] = read_metrics(path);
  if (has("target.ply", path))
    data["target"] = tri_mesh_json(read_mesh(path), Quantizer(options.quantum_mm, path));
  if (has("stitch_mesh.ply", path))
    data["stitch_mesh"] = stitch_mesh_json(path, Quantizer(options.quantum_mm, path));
  // A stitch mesh or a plain triangle mesh, with its kind.
  auto either_mesh = [&](const std::string& file) {
    const Quantizer q(options.quantum_mm, file);
    const bool stitches = ply_has_stitch_types(file);
    json r = stitches ? stitch_mesh_json(file, q) : tri_mesh_json(read_mesh(file), q);
    r["kind"] = stitches ? "stitch_mesh" : "mesh";
    return r;
  };
  if (has("relaxed.ply", path)) data["relaxed"] = either_mesh(path);
  if (has("predicted.ply", path)) data["predicted"] = either_mesh(path);
  if (has("knitting_map.csv", path)) data["map"] = map_json(read_knitting_map_csv(path));
  if (has("wales.obj", path)) {
    data["wales"] = polylines_json(read_polylines_obj(path), Quantizer(options.quantum_mm, path),
                                   options.max_polyline_points, "wales.obj", notes);
  }
  if (has("yarn.obj", path)) {
    data["yarn"] = polylines_json(read_polylines_obj(path), Quantizer(options.quantum_mm, path),
                                  options.max_polyline_points, "yarn.obj", notes);
  }
  if (has("knitout.k", path)) data["knitout"] = knitout_json(path, options.simulate_knitout);
  // The animation of `cloth` (not listed as missing elsewhere).
  path = (fs::path(outdir) / "animation.glb").string();
  if (fs::is_regular_file(path, ec)) {
    files.push_back(json{{"name", "animation.glb"}, {"bytes", static_cast<uint64_t>(fs::file_size(path, ec))}});
    json a = animation_json(path, (fs::path(outdir) / "cloth.json").string(), data,
                            Quantizer(options.quantum_mm, path), options.max_animation_values, files, notes);
    if (!a.is_null()) data["animation"] = std::move(a);
  }

  if (files.empty()) {
    std::string list;
    for (const std::string& n : report_input_files()) list += (list.empty() ? "" : ", ") + n;
    throw IOError(
        fmt::format("{}: nothing to report: the directory holds none of {}; give the output directory "
                    "of a design command",
                    outdir, list));
  }
  if (!missing.empty()) {
    std::string list;
    for (const std::string& n : missing) list += (list.empty() ? "" : ", ") + n;
    notes.push_back("not in the output directory: " + list);
  }
  data["files"] = std::move(files);
  data["notes"] = std::move(notes);
  return data;
}

std::string_view report_viewer_script() {
  static const std::string script = [] {
    std::string s;
    for (std::size_t i = 0; i < report_detail::kViewerScriptChunkCount; ++i)
      s += report_detail::kViewerScriptChunks[i];
    return s;
  }();
  return script;
}

std::string report_html_page(const json& data) {
  std::string title =
      data.contains("title") && data["title"].is_string() ? data["title"].get<std::string>() : "";
  std::string esc;
  for (char c : title) {
    switch (c) {
      case '<':
        esc += "&lt;";
        break;
      case '>':
        esc += "&gt;";
        break;
      case '&':
        esc += "&amp;";
        break;
      case '"':
        esc += "&quot;";
        break;
      default:
        esc += c;
    }
  }
  const std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string page;
  const std::string_view script = report_viewer_script();
  page.reserve(text.size() + script.size() + 1024);
  page +=
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta name=\"generator\" content=\"knitforge\">\n<title>knitforge report: ";
  page += esc;
  page += "</title>\n</head>\n<body>\n<script type=\"application/json\" id=\"knitforge-data\">";
  // '<' only occurs inside JSON strings, where \u003c means the same.
  for (char c : text) {
    if (c == '<')
      page += "\\u003c";
    else
      page += c;
  }
  page += "</script>\n<script>\n";
  page += script;
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

void write_report_html(const std::string& outdir, const ReportHtmlOptions& options) {
  const json data = report_data(outdir, options);
  const std::string page = report_html_page(data);
  const std::string out =
      options.output.empty() ? (fs::path(outdir) / "report.html").string() : options.output;
  write_file_atomically(
      out, [&](std::ostream& os) { os.write(page.data(), static_cast<std::streamsize>(page.size())); }, true);
}

}  // namespace knitforge
