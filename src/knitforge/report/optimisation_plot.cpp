#include "knitforge/report/optimisation_plot.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "knitforge/util/errors.h"

namespace knitforge {

namespace {

nlohmann::json bvec(const BoundaryVector& b) { return {b[0], b[1], b[2], b[3]}; }

/// A "nice" tick step for a range.
double tick_step(double range, int ticks) {
  const double raw = range / std::max(1, ticks);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

}  // namespace

std::string optimisation_plot_svg(const BoundaryOptimisation& opt, int width, int height) {
  if (opt.history.empty()) throw InvalidInput("optimisation plot: no evaluations");
  if (width < 200 || height < 150) throw InvalidInput("optimisation plot: the picture must be at least 200 x 150 px");
  const int n = static_cast<int>(opt.history.size());
  double lo = opt.history[0].value, hi = lo;
  for (const auto& e : opt.history) lo = std::min(lo, e.value), hi = std::max(hi, e.value);
  if (!(hi > lo)) hi = lo + 1.0;
  const double step = tick_step(hi - lo, 6);
  lo = std::floor(lo / step) * step;
  hi = std::ceil(hi / step) * step;
  const double L = 64, R = 16, T = 30, B = 44;
  const double pw = width - L - R, ph = height - T - B;
  auto X = [&](double i) { return L + (n > 1 ? i / (n - 1) : 0.5) * pw; };
  auto Y = [&](double v) { return T + (hi - v) / (hi - lo) * ph; };
  std::ostringstream s;
  s << fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="sans-serif" font-size="12">)",
                   width, height, width, height)
    << "\n";
  s << fmt::format(R"(<rect width="{}" height="{}" fill="white"/>)", width, height) << "\n";
  s << fmt::format(R"(<text x="{}" y="18" font-size="13">short-column optimisation{}: estimated transfer stitches (3/2 I / sw) per evaluation</text>)",
                   L, opt.symmetric ? " (symmetric)" : "")
    << "\n";
  for (double v = lo; v <= hi + 1e-9 * step; v += step) {
    s << fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#ddd"/>)", L, Y(v), L + pw, Y(v)) << "\n";
    s << fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="end">{:g}</text>)", L - 6, Y(v) + 4, v) << "\n";
  }
  const double xs = tick_step(std::max(1, n - 1), 8);
  for (double i = 0; i <= n - 1 + 1e-9; i += xs)
    s << fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{:g}</text>)", X(i), T + ph + 16, i + 1) << "\n";
  s << fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">evaluation</text>)", L + pw / 2, height - 8.0) << "\n";
  s << fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#444"/>)", L, T, pw, ph) << "\n";
  // Best so far.
  std::string path;
  for (int i = 0; i < n; ++i) path += fmt::format("{}{:.1f},{:.1f}", i ? " L" : "M", X(i), Y(opt.history[i].best));
  s << fmt::format(R"(<path d="{}" fill="none" stroke="#c0392b" stroke-width="2"/>)", path) << "\n";
  for (int i = 0; i < n; ++i) {
    const auto& e = opt.history[i];
    const char* colour = e.initial ? "#999" : "#1f5fa8";
    s << fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="3.5" fill="{}" stroke="{}"/>)", X(i), Y(e.value),
                     e.projected ? "white" : colour, colour)
      << "\n";
  }
  for (size_t k = 0; k < opt.alternatives.size(); ++k) {
    const int i = opt.alternatives[k];
    s << fmt::format(R"(<text x="{:.1f}" y="{:.1f}" fill="#c0392b" font-weight="bold">{}</text>)", X(i) + 5,
                     Y(opt.history[static_cast<size_t>(i)].value) - 5, k + 1)
      << "\n";
  }
  const double ly = T + 14;
  s << fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="3.5" fill="#999"/><text x="{:.1f}" y="{:.1f}">initial design</text>)",
                   L + pw - 300, ly, L + pw - 292, ly + 4)
    << fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="3.5" fill="white" stroke="#1f5fa8"/><text x="{:.1f}" y="{:.1f}">projected (eq. 3.9)</text>)",
                   L + pw - 200, ly, L + pw - 192, ly + 4)
    << fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#c0392b" stroke-width="2"/><text x="{:.1f}" y="{:.1f}">best so far</text>)",
                   L + pw - 80, ly, L + pw - 64, ly, L + pw - 60, ly + 4)
    << "\n</svg>\n";
  return s.str();
}

nlohmann::json optimisation_json(const BoundaryOptimisation& opt) {
  nlohmann::json ev = nlohmann::json::array();
  for (size_t i = 0; i < opt.history.size(); ++i) {
    const auto& e = opt.history[i];
    ev.push_back({{"index", i},
                  {"suggested", bvec(e.suggested)},
                  {"evaluated", bvec(e.evaluated)},
                  {"projected", e.projected},
                  {"initial", e.initial},
                  {"region", e.region},
                  {"metric_mm", e.metric},
                  {"estimated_transfers", e.value},
                  {"penalised", e.penalised},
                  {"best_so_far", e.best},
                  {"trust_length", e.trust_length}});
  }
  nlohmann::json alt = nlohmann::json::array();
  for (int i : opt.alternatives)
    alt.push_back({{"index", i},
                   {"b", bvec(opt.history[static_cast<size_t>(i)].evaluated)},
                   {"estimated_transfers", opt.history[static_cast<size_t>(i)].value}});
  nlohmann::json j = {{"best", {{"b", bvec(opt.best)}, {"estimated_transfers", opt.best_value}}},
                      {"evaluations", ev},
                      {"alternatives", alt},
                      {"trust_regions", opt.regions},
                      {"unplaceable_evaluations", opt.unplaceable},
                      {"symmetric", opt.symmetric},
                      {"proxy", {{"faces", opt.proxy_faces}, {"vertices", opt.proxy_vertices}, {"edge_length_mm", opt.proxy_edge_length}}},
                      {"seconds", {{"total", opt.seconds}, {"proxy", opt.seconds_proxy}, {"evaluations", opt.seconds_evaluations}}}};
  if (opt.symmetric)
    j["mirror"] = {{"normal", {opt.mirror.normal.x(), opt.mirror.normal.y(), opt.mirror.normal.z()}},
                   {"offset_mm", opt.mirror.offset},
                   {"mean_error_mm", opt.mirror_error},
                   {"p", opt.mirror_p},
                   {"gap", opt.mirror_gap}};
  return j;
}

}  // namespace knitforge
