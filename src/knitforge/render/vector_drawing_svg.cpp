#include <cmath>
#include <map>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/render/vector_drawing.h"
#include "knitforge/util/errors.h"

namespace knitforge {

std::string vector_drawing_svg(const VectorDrawing& d, const SvgOptions& o) {
  if (o.width < 1) throw InvalidInput(fmt::format("SVG width = {} must be at least 1 px", o.width));
  if (!(o.stroke_width >= 0.0) || !std::isfinite(o.stroke_width)) {
    throw InvalidInput("SVG stroke width must be >= 0 px");
  }
  if (!(d.aspect > 0.0) || !std::isfinite(d.aspect))
    throw InvalidInput("vector drawing: aspect must be positive");
  const double w = o.width;
  const double h = std::max(1.0, std::round(w / d.aspect));
  auto px = [&](const Vec2& p) {
    return fmt::format("{:.3f} {:.3f}", 0.5 * (p.x() + 1.0) * w, 0.5 * (1.0 - p.y()) * h);
  };
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\">\n",
      static_cast<int>(w), static_cast<int>(h));
  if (o.background) s += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  if (o.fill) {
    s += "<g id=\"regions\" stroke=\"none\" fill-rule=\"evenodd\">\n";
    for (const DrawingRegion& r : d.regions) {
      s += fmt::format("<path data-mesh=\"{}\" fill=\"#{:02x}{:02x}{:02x}\" d=\"", r.mesh, r.colour[0],
                       r.colour[1], r.colour[2]);
      for (const auto& ring : r.rings) {
        for (size_t i = 0; i < ring.size(); ++i) {
          s += i == 0 ? "M" : " L";
          s += px(ring[i]);
        }
        s += " Z";
      }
      s += "\"/>\n";
    }
    s += "</g>\n";
  }
  std::map<int, std::string> paths;  // per mesh, in mesh order
  for (const DrawingEdge& e : d.edges) {
    std::string& p = paths[e.mesh];
    p += 'M';
    p += px(e.a);
    p += " L";
    p += px(e.b);
    p += ' ';
  }
  s += fmt::format(
      "<g id=\"contours\" fill=\"none\" stroke=\"#{:02x}{:02x}{:02x}\" stroke-width=\"{}\" "
      "stroke-linecap=\"round\" "
      "stroke-linejoin=\"round\">\n",
      o.stroke[0], o.stroke[1], o.stroke[2], o.stroke_width);
  for (auto& [mesh, path] : paths) {
    if (!path.empty()) path.pop_back();
    s += fmt::format("<path data-mesh=\"{}\" d=\"{}\"/>\n", mesh, path);
  }
  s += "</g>\n</svg>\n";
  return s;
}

}  // namespace knitforge
