#include "knitforge/io/io_detail.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>

#include "knitforge/geometry/halfedges.h"
#include "knitforge/util/errors.h"

namespace knitforge::io_detail {

std::string load_file(const std::string& path) {
  {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      throw IOError(fmt::format("{}: is a directory, not a file; give the path of a file", path));
    }
  }
  std::ifstream in(path, std::ios::in | std::ios::binary);
  if (!in) {
    throw IOError(fmt::format("{}: cannot open file ({}); check the path", path, std::strerror(errno)));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw IOError(fmt::format("{}: read error", path));
  return std::move(ss).str();
}

std::string extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

std::string where(const std::string& path, LocKind kind, int64_t loc) {
  return kind == LocKind::Line ? fmt::format("{}:{}: ", path, loc) : fmt::format("{}: byte {}: ", path, loc);
}

std::string printable_message(std::string_view message) {
  // Quoted spans ('...') are input echoed back: at most 80 characters of
  // them are kept; any byte that is not printable ASCII becomes '?'.
  std::string out;
  out.reserve(std::min<size_t>(message.size(), 400));
  bool quoted = false;
  size_t quoted_len = 0, cut = 0;
  for (const char ch : message) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c == '\'') {
      if (quoted && cut > 0) out += fmt::format("...' ({} more characters)", cut), cut = 0;
      else out += '\'';
      quoted = !quoted;
      quoted_len = 0;
      continue;
    }
    if (quoted && ++quoted_len > 80) {
      ++cut;
      continue;
    }
    out += (c >= 0x20 && c < 0x7f) ? ch : '?';
  }
  if (quoted && cut > 0) out += fmt::format("... ({} more characters)", cut);
  return out;
}

void fail_line(const std::string& path, int64_t line, std::string_view message) {
  throw IOError(fmt::format("{}:{}: {}", path, line, printable_message(message)));
}

void fail_byte(const std::string& path, int64_t offset, std::string_view message) {
  throw IOError(fmt::format("{}: byte {}: {}", path, offset, printable_message(message)));
}

LineReader::LineReader(std::string_view text, bool strip_bom) : text_(text) {
  if (strip_bom && text_.size() >= 3 && text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const size_t nl = text_.find('\n', pos_);
  const size_t end = nl == std::string_view::npos ? text_.size() : nl;
  line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = nl == std::string_view::npos ? text_.size() : nl + 1;
  ++line_;
  return true;
}

void split_ws(std::string_view s, std::vector<std::string_view>& out) {
  out.clear();
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r')) ++i;
    size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t' && s[j] != '\r') ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
}

std::vector<std::string_view> split_ws(std::string_view s) {
  std::vector<std::string_view> out;
  split_ws(s, out);
  return out;
}

std::string_view trim(std::string_view s) {
  auto ws = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && ws(s.front())) s.remove_prefix(1);
  while (!s.empty() && ws(s.back())) s.remove_suffix(1);
  return s;
}

std::string_view strip_comment(std::string_view s) {
  const size_t h = s.find('#');
  return h == std::string_view::npos ? s : s.substr(0, h);
}

bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool parse_int64(std::string_view s, int64_t& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool host_little_endian() { return std::endian::native == std::endian::little; }

std::string format_double(double v) { return fmt::format("{}", v); }

namespace {

// Indices following "face"/"faces" in a message: "face 3", "faces 3 and 4",
// "faces (1, 2, 3)".
std::vector<int64_t> faces_in_message(std::string_view msg) {
  std::vector<int64_t> out;
  size_t pos = 0;
  while ((pos = msg.find("face", pos)) != std::string_view::npos) {
    const bool word_start = pos == 0 || !std::isalpha(static_cast<unsigned char>(msg[pos - 1]));
    size_t i = pos + 4;
    pos = i;
    if (!word_start) continue;
    if (i < msg.size() && msg[i] == 's') ++i;
    while (true) {
      while (i < msg.size() && (msg[i] == ' ' || msg[i] == '(' || msg[i] == ',')) ++i;
      if (msg.substr(i, 4) == "and ") i += 4;
      size_t j = i;
      while (j < msg.size() && std::isdigit(static_cast<unsigned char>(msg[j]))) ++j;
      if (j == i) break;
      int64_t f = 0;
      std::from_chars(msg.data() + i, msg.data() + j, f);
      out.push_back(f);
      i = j;
    }
    pos = i;
  }
  return out;
}

int64_t vertex_in_message(std::string_view msg) {
  const size_t pos = msg.find("vertex ");
  if (pos == std::string_view::npos) return -1;
  size_t i = pos + 7, j = i;
  while (j < msg.size() && std::isdigit(static_cast<unsigned char>(msg[j]))) ++j;
  if (j == i) return -1;
  int64_t v = -1;
  std::from_chars(msg.data() + i, msg.data() + j, v);
  return v;
}

}  // namespace

void check_polygon_mesh(const std::string& path, int num_vertices, const std::vector<int>& face_start,
                        const std::vector<int>& face_vertices, const std::vector<int64_t>& face_loc,
                        LocKind kind) {
  try {
    (void)build_halfedges(num_vertices, face_start, face_vertices);
  } catch (const TopologyError& e) {
    const std::string_view msg = e.what();
    const char* unit = kind == LocKind::Line ? "line" : "byte";
    std::vector<int64_t> faces;
    for (int64_t f : faces_in_message(msg)) {
      if (f >= 0 && f < static_cast<int64_t>(face_loc.size())) faces.push_back(f);
    }
    std::string detail;
    if (!faces.empty()) {
      detail = " [";
      for (size_t k = 0; k < faces.size(); ++k) {
        detail += fmt::format("{}face {} at {} {}", k ? ", " : "", faces[k], unit, face_loc[faces[k]]);
      }
      detail += "; faces and vertices count from 0]";
      // The latest face in the file is the one that broke the mesh (the
      // third face on an edge, the second of two clashing orientations).
      const int64_t worst = *std::max_element(faces.begin(), faces.end());
      throw IOError(where(path, kind, face_loc[worst]) + std::string(msg) + detail);
    }
    const int64_t v = vertex_in_message(msg);
    const int nf = static_cast<int>(face_start.size()) - 1;
    for (int f = 0; v >= 0 && f < nf; ++f) {
      for (int i = face_start[f]; i < face_start[f + 1]; ++i) {
        if (face_vertices[i] != v) continue;
        detail = fmt::format(" [vertex {} is first used by face {} at {} {}; faces and vertices "
                             "count from 0]",
                             v, f, unit, face_loc[f]);
        throw IOError(where(path, kind, face_loc[f]) + std::string(msg) + detail);
      }
    }
    throw IOError(fmt::format("{}: {}", path, msg));
  }
}

void check_mesh(const std::string& path, const TriMesh& mesh, const std::vector<int64_t>& face_loc,
                LocKind kind) {
  if (mesh.faces.empty()) {
    throw IOError(fmt::format("{}: the file holds {} vertices but no faces; a surface mesh needs "
                              "triangles or polygons",
                              path, mesh.vertices.size()));
  }
  std::vector<int> start(mesh.faces.size() + 1), verts(3 * mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    start[f + 1] = static_cast<int>(3 * (f + 1));
    for (int k = 0; k < 3; ++k) verts[3 * f + k] = mesh.faces[f][k];
  }
  check_polygon_mesh(path, mesh.num_vertices(), start, verts, face_loc, kind);
}

void check_mesh_for_writing(const std::string& path, const TriMesh& mesh,
                            const MeshWriteOptions& options, std::string_view format,
                            bool vertex_colours_supported, bool face_colours_supported) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (!mesh.vertices[v].allFinite()) {
      throw InvalidInput(fmt::format("{}: vertex {} has a non-finite coordinate; cannot write it",
                                     path, v));
    }
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.faces[f][k];
      if (i < 0 || i >= mesh.num_vertices()) {
        throw InvalidInput(fmt::format("{}: face {} uses vertex {}, but the mesh has {} vertices",
                                       path, f, i, mesh.num_vertices()));
      }
    }
  }
  if (!options.vertex_colours.empty()) {
    if (!vertex_colours_supported) {
      throw InvalidInput(fmt::format("{}: {} cannot store vertex colours; write .ply instead", path,
                                     format));
    }
    if (options.vertex_colours.size() != mesh.vertices.size()) {
      throw InvalidInput(fmt::format("{}: {} vertex colours given for {} vertices", path,
                                     options.vertex_colours.size(), mesh.vertices.size()));
    }
  }
  if (!options.face_colours.empty()) {
    if (!face_colours_supported) {
      throw InvalidInput(fmt::format("{}: {} cannot store face colours; write .ply instead", path,
                                     format));
    }
    if (options.face_colours.size() != mesh.faces.size()) {
      throw InvalidInput(fmt::format("{}: {} face colours given for {} faces", path,
                                     options.face_colours.size(), mesh.faces.size()));
    }
  }
}

}  // namespace knitforge::io_detail
