#include "knitforge/io/knitting_map_image.h"

#include <array>
#include <ostream>
#include <set>

#include <fmt/core.h>

#include "knitforge/io/colours.h"
#include "knitforge/io/io_detail.h"
#include "knitforge/io/png_image.h"
#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

constexpr Rgb kGridColour{150, 150, 150};
constexpr Rgb kTextColour{40, 40, 40};
constexpr Rgb kFoldColour{20, 20, 20};    // a tube's fold between its front and back halves
constexpr Rgb kSeamColour{215, 25, 28};   // where a round of a tube starts

void check_map(const KnittingMap& map, const MapImageOptions& options) {
  if (map.rows < 0 || map.cols < 0 || map.cells.size() != static_cast<size_t>(map.rows) * map.cols ||
      map.direction.size() != static_cast<size_t>(map.rows) ||
      (!map.yarn.empty() && map.yarn.size() != map.cells.size())) {
    throw InvalidInput(fmt::format("knitting map {}x{}: cells ({}), direction ({}) or yarn ({}) have the "
                                   "wrong size",
                                   map.rows, map.cols, map.cells.size(), map.direction.size(), map.yarn.size()));
  }
  check_map_arrays(map);  // seams
  for (size_t i = 0; i < map.cells.size(); ++i) {
    if (static_cast<int>(map.cells[i]) > static_cast<int>(CellType::Empty)) {
      throw InvalidInput(fmt::format("knitting map cell ({}, {}) has unknown type {}", i / map.cols,
                                     i % map.cols, static_cast<int>(map.cells[i])));
    }
  }
  if (options.cell_size < 4) {
    throw InvalidInput(fmt::format("map image cell size {} is too small; use at least 4", options.cell_size));
  }
}

Rgb cell_fill(const KnittingMap& map, int r, int c, const MapImageOptions& options) {
  const CellType t = map.at(r, c);
  Rgb fill = map_cell_background(t, map.direction[r]);
  const int y = map.yarn_at(r, c);
  if (options.yarn_tint && y != 0 && is_stitch(t)) fill = mix(fill, yarn_colour(y), 0.45);
  return fill;
}

// Corners of the glyph of a shaping stitch in a cell [x0, x0+s] x [y0, y0+s]
// (y down), apex first.
std::array<std::array<double, 2>, 3> glyph(StitchType t, double x0, double y0, double s) {
  const double m = std::max(1.0, s / 6.0);
  const double l = x0 + m, rgt = x0 + s - m, top = y0 + m, bot = y0 + s - m;
  const double xc = x0 + s / 2, yc = y0 + s / 2;
  switch (t) {
    case StitchType::ShortRowLeft: return {{{l, yc}, {rgt, bot}, {rgt, top}}};
    case StitchType::ShortRowRight: return {{{rgt, yc}, {l, top}, {l, bot}}};
    case StitchType::Increase: return {{{xc, bot}, {rgt, top}, {l, top}}};
    case StitchType::Decrease: return {{{xc, top}, {l, bot}, {rgt, bot}}};
    case StitchType::Knit: break;
  }
  return {};
}

bool inside(const std::array<std::array<double, 2>, 3>& t, double x, double y) {
  auto side = [&](int i, int j) {
    return (t[j][0] - t[i][0]) * (y - t[i][1]) - (t[j][1] - t[i][1]) * (x - t[i][0]);
  };
  const double a = side(0, 1), b = side(1, 2), c = side(2, 0);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}

std::string hex(Rgb c) { return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b); }

}  // namespace

void write_knitting_map_png(const std::string& path, const KnittingMap& map, const MapImageOptions& options) {
  check_map(map, options);
  const int s = options.cell_size;
  const int64_t w64 = static_cast<int64_t>(map.cols) * s + 1, h64 = static_cast<int64_t>(map.rows) * s + 1;
  if (w64 * h64 > (int64_t{1} << 27)) {
    throw InvalidInput(fmt::format("{}: a {}x{} map at {} pixels per cell is a {}x{} picture, too large; use a "
                                   "smaller cell size or write .svg",
                                   path, map.rows, map.cols, s, w64, h64));
  }
  const int w = static_cast<int>(w64), h = static_cast<int>(h64);
  RgbImage image;
  image.width = w;
  image.height = h;
  image.pixels.assign(static_cast<size_t>(w) * h * 3, 255);
  std::vector<uint8_t>& pixels = image.pixels;
  auto put = [&](int x, int y, Rgb c) {
    uint8_t* p = &pixels[(static_cast<size_t>(y) * w + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  };
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const int x0 = c * s, y0 = (map.rows - 1 - r) * s;
      const Rgb fill = cell_fill(map, r, c, options);
      const CellType t = map.at(r, c);
      const bool shaped = is_stitch(t) && to_stitch_type(t) != StitchType::Knit;
      const auto tri = shaped ? glyph(to_stitch_type(t), x0, y0, s) : decltype(glyph(StitchType::Knit, 0, 0, 0)){};
      const Rgb gc = shaped ? stitch_type_colour(to_stitch_type(t)) : Rgb{};
      for (int y = y0 + 1; y < y0 + s; ++y) {
        for (int x = x0 + 1; x < x0 + s; ++x) {
          put(x, y, shaped && inside(tri, x + 0.5, y + 0.5) ? gc : fill);
        }
      }
    }
  }
  for (int y = 0; y < h; y += s) {
    for (int x = 0; x < w; ++x) put(x, y, kGridColour);
  }
  for (int x = 0; x < w; x += s) {
    for (int y = 0; y < h; ++y) put(x, y, kGridColour);
  }
  if (map.tubular()) {
    // The fold between the halves: a double line; each round's seam: its
    // grid line drawn red, two pixels wide where the picture has room.
    const int xf = map.tube_half() * s;
    for (int y = 0; y < h; ++y)
      for (int x = std::max(0, xf - 1); x <= std::min(w - 1, xf + 1); ++x) put(x, y, kFoldColour);
    for (int r = 0; r < map.rows; ++r) {
      if (!map.closed(r)) continue;
      const int xs = map.seam[static_cast<size_t>(r)] * s, y0 = (map.rows - 1 - r) * s;
      for (int y = y0; y <= y0 + s && y < h; ++y)
        for (int x = xs; x <= std::min(w - 1, xs + 1); ++x) put(x, y, kSeamColour);
    }
  }
  write_png(path, image);
}

std::string knitting_map_svg(const KnittingMap& map, const MapImageOptions& options) {
  check_map(map, options);
  const int s = options.cell_size;
  const int font = std::clamp(s, 8, 12);
  const int ml = 6 * font / 2 + 8;  // room for course labels
  const int mt = 8, mb = (map.tubular() ? 2 : 1) * (font + 10);
  const int map_w = map.cols * s, map_h = map.rows * s;

  // Legend entries: swatch kind and label.
  struct Entry {
    CellType type;
    int dir;
    int yarn;
    std::string label;
  };
  std::vector<Entry> legend = {
      {CellType::Knit, 1, 0, "knit, row left to right"},
      {CellType::Knit, -1, 0, "knit, row right to left"},
      {CellType::ShortRowLeft, 1, 0, "short row, left end"},
      {CellType::ShortRowRight, 1, 0, "short row, right end"},
      {CellType::Increase, 1, 0, "increase (short column starts)"},
      {CellType::Decrease, 1, 0, "decrease (short column ends)"},
      {CellType::Collapsed, 1, 0, "collapsed"},
      {CellType::Empty, 1, 0, "empty"},
  };
  if (options.yarn_tint) {
    std::set<int> yarns;
    for (int r = 0; r < map.rows; ++r) {
      for (int c = 0; c < map.cols; ++c) {
        if (map.yarn_at(r, c) != 0 && is_stitch(map.at(r, c))) yarns.insert(map.yarn_at(r, c));
      }
    }
    for (int y : yarns) legend.push_back({CellType::Knit, 1, y, fmt::format("yarn {}", y)});
  }
  const int sw = 12, line_h = 18;
  const int lx = ml + map_w + 20;
  const int legend_h = static_cast<int>(legend.size() + (map.tubular() ? 2 : 0)) * line_h;
  const int width = lx + sw + 8 + 200;
  const int height = mt + std::max(map_h + mb, legend_h) + 8;

  std::string o;
  o += fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"{2}\">\n"
      "<title>knitting map {3} rows x {4} columns</title>\n"
      "<rect x=\"0\" y=\"0\" width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
      width, height, font, map.rows, map.cols);
  const std::string grid = hex(kGridColour);
  o += fmt::format("<g class=\"cells\" stroke=\"{}\" stroke-width=\"0.5\">\n", grid);
  std::string glyphs;
  for (int r = map.rows - 1; r >= 0; --r) {
    for (int c = 0; c < map.cols; ++c) {
      const int x0 = ml + c * s, y0 = mt + (map.rows - 1 - r) * s;
      o += fmt::format("<rect class=\"cell\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>\n", x0, y0,
                       s, s, hex(cell_fill(map, r, c, options)));
      const CellType t = map.at(r, c);
      if (is_stitch(t) && t != CellType::Knit) {
        const auto tri = glyph(to_stitch_type(t), x0, y0, s);
        glyphs += fmt::format("<polygon class=\"glyph\" points=\"{:g},{:g} {:g},{:g} {:g},{:g}\" fill=\"{}\"/>\n",
                              tri[0][0], tri[0][1], tri[1][0], tri[1][1], tri[2][0], tri[2][1],
                              hex(stitch_type_colour(to_stitch_type(t))));
      }
    }
  }
  o += "</g>\n<g class=\"glyphs\">\n" + glyphs + "</g>\n";
  if (map.tubular()) {
    const int xf = ml + map.tube_half() * s;
    o += fmt::format("<g class=\"tube\">\n<line class=\"fold\" x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" "
                     "stroke=\"{3}\" stroke-width=\"2\"/>\n",
                     xf, mt, mt + map_h, hex(kFoldColour));
    for (int r = 0; r < map.rows; ++r) {
      if (!map.closed(r)) continue;
      const int xs = ml + map.seam[static_cast<size_t>(r)] * s, y0 = mt + (map.rows - 1 - r) * s;
      o += fmt::format("<line class=\"seam\" x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"{3}\" "
                       "stroke-width=\"2\"/>\n",
                       xs, y0, y0 + s, hex(kSeamColour));
    }
    o += fmt::format("<text class=\"half-label\" x=\"{:g}\" y=\"{}\" text-anchor=\"middle\">front</text>\n"
                     "<text class=\"half-label\" x=\"{:g}\" y=\"{}\" text-anchor=\"middle\">back</text>\n</g>\n",
                     ml + map.tube_half() * s / 2.0, mt + map_h + 2 * font + 8,
                     ml + (map.tube_half() + map.cols) * s / 2.0, mt + map_h + 2 * font + 8);
  }
  o += fmt::format("<g class=\"labels\" fill=\"{}\">\n", hex(kTextColour));
  for (int r = 0; r < map.rows; r += 10) {
    o += fmt::format("<text class=\"course-label\" x=\"{}\" y=\"{:g}\" text-anchor=\"end\" "
                     "dominant-baseline=\"middle\">{}</text>\n",
                     ml - 4, mt + (map.rows - 1 - r) * s + s / 2.0, r);
  }
  for (int c = 0; c < map.cols; c += 10) {
    o += fmt::format("<text class=\"wale-label\" x=\"{:g}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     ml + c * s + s / 2.0, mt + map_h + font + 4, c);
  }
  o += "</g>\n<g class=\"legend\">\n";
  for (size_t i = 0; i < legend.size(); ++i) {
    const Entry& e = legend[i];
    const int y0 = mt + static_cast<int>(i) * line_h;
    Rgb fill = map_cell_background(e.type, e.dir);
    if (e.yarn != 0) fill = mix(fill, yarn_colour(e.yarn), 0.45);
    o += fmt::format("<rect class=\"legend-swatch\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" "
                     "stroke=\"{}\" stroke-width=\"0.5\"/>\n",
                     lx, y0, sw, sw, hex(fill), grid);
    if (is_stitch(e.type) && e.type != CellType::Knit) {
      const auto tri = glyph(to_stitch_type(e.type), lx, y0, sw);
      o += fmt::format("<polygon class=\"legend-glyph\" points=\"{:g},{:g} {:g},{:g} {:g},{:g}\" fill=\"{}\"/>\n",
                       tri[0][0], tri[0][1], tri[1][0], tri[1][1], tri[2][0], tri[2][1],
                       hex(stitch_type_colour(to_stitch_type(e.type))));
    }
    o += fmt::format("<text x=\"{}\" y=\"{}\" dominant-baseline=\"middle\" fill=\"{}\">{}</text>\n", lx + sw + 6,
                     y0 + sw / 2, hex(kTextColour), e.label);
  }
  if (map.tubular()) {
    const int y0 = mt + static_cast<int>(legend.size()) * line_h;
    o += fmt::format("<line class=\"legend-fold\" x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"{3}\" "
                     "stroke-width=\"2\"/>\n<text x=\"{4}\" y=\"{5}\" dominant-baseline=\"middle\">fold: front "
                     "half | back half</text>\n",
                     lx + sw / 2, y0, y0 + sw, hex(kFoldColour), lx + sw + 6, y0 + sw / 2);
    o += fmt::format("<line class=\"legend-seam\" x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"{3}\" "
                     "stroke-width=\"2\"/>\n<text x=\"{4}\" y=\"{5}\" dominant-baseline=\"middle\">seam: where the "
                     "round starts</text>\n",
                     lx + sw / 2, y0 + line_h, y0 + line_h + sw, hex(kSeamColour), lx + sw + 6,
                     y0 + line_h + sw / 2);
  }
  o += "</g>\n</svg>\n";
  return o;
}

void write_knitting_map_svg(const std::string& path, const KnittingMap& map, const MapImageOptions& options) {
  const std::string svg = knitting_map_svg(map, options);
  write_file_atomically(path, [&](std::ostream& o) { o << svg; }, true);
}

void write_knitting_map_image(const std::string& path, const KnittingMap& map, const MapImageOptions& options) {
  const std::string ext = io_detail::extension(path);
  if (ext == "png") return write_knitting_map_png(path, map, options);
  if (ext == "svg") return write_knitting_map_svg(path, map, options);
  throw InvalidInput(fmt::format("{}: unknown picture format '.{}'; use .png or .svg", path, ext));
}

}  // namespace knitforge
