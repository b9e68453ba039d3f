// Example 06: does the divergence metric predict the transfer count? (seed Fig. 3.16)
//
// N random feasible boundary vectors b (eq. 3.8, drawn uniformly through
// boundary_from_unit()) on the built-in hemisphere (r 75 mm, 2.5 mm edges,
// stitch 3.5 x 2.8 mm); for each the harmonic field is solved and the whole
// short-column route run (design_short_columns(), no evaluation), as
// `knitforge shortcolumn hemisphere --bc b --no-evaluate` does. Per b one
// line: b, the metric's estimate 3/2 I / sw, the actual transfer count
// (increases + decreases), knittable or not and, when not, where it failed
// (the stage that threw, or the knittability rules broken). Then the share
// of knittable designs, the Pearson r between estimate and transfers, the
// least-squares line, and the scatter as an SVG (OUTDIR/metric_vs_transfers.svg)
// with the per-b table as CSV (OUTDIR/metric_vs_transfers.csv).
//
//   build/examples/example_06_metric_vs_transfers [OUTDIR [N [SEED]]]   (out/fig316, 60, 16)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "knitforge/design/shortcolumn/boundary_intervals.h"
#include "knitforge/design/shortcolumn/design_short_columns.h"
#include "knitforge/design/shortcolumn/feasible_set.h"
#include "knitforge/design/shortcolumn/harmonic_field.h"
#include "knitforge/geometry/shapes.h"
#include "knitforge/util/errors.h"

namespace {

struct Trial {
  knitforge::BoundaryVector b;
  double estimate = 0.0;
  int transfers = -1;  ///< -1: no design (a stage threw)
  bool knittable = false;
  std::string failure;  ///< "" when knittable
  int stitches = 0;
  double stitches_vs_area = 0.0;  ///< stitches / (area / (sw sh)) - 1
  double uncovered = 0.0;         ///< mm^2 no strip covers (ColumnWales::uncovered_area)
  int joined = 0, tiny = 0, sampleless = 0;  ///< ColumnWales counters
};

/// The rules a report breaks, as "rule xN, rule xM".
std::string broken_rules(const knitforge::KnittabilityReport& r, const char* what) {
  std::string s;
  for (int k = 0; k < knitforge::kNumKnitRules; ++k) {
    const auto rule = static_cast<knitforge::KnitRule>(k);
    if (r.counts[static_cast<size_t>(k)] == 0 || knitforge::rule_severity(rule) != knitforge::Severity::Error) continue;
    s += fmt::format("{}{} {} x{}", s.empty() ? "" : ", ", what, knitforge::rule_id(rule), r.counts[static_cast<size_t>(k)]);
  }
  return s;
}

std::string scatter_svg(const std::vector<Trial>& trials, double slope, double offset, double r) {
  const int W = 640, H = 440;
  const double L = 60, R = 16, T = 34, B = 46;
  double xmax = 1.0, ymax = 1.0;
  for (const Trial& t : trials) {
    if (t.transfers < 0) continue;
    xmax = std::max(xmax, t.estimate);
    ymax = std::max(ymax, static_cast<double>(t.transfers));
  }
  auto nice = [](double v) {
    const double p = std::pow(10.0, std::floor(std::log10(v)));
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
      if (m * p >= v) return m * p;
    return 10.0 * p;
  };
  xmax = nice(xmax * 1.05);
  ymax = nice(ymax * 1.05);
  const double pw = W - L - R, ph = H - T - B;
  auto X = [&](double v) { return L + v / xmax * pw; };
  auto Y = [&](double v) { return T + (1.0 - v / ymax) * ph; };
  std::ostringstream s;
  s << fmt::format(R"~(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="sans-serif" font-size="12">)~",
                   W, H, W, H)
    << "\n"
    << fmt::format(R"~(<rect width="{}" height="{}" fill="white"/>)~", W, H) << "\n"
    << fmt::format(R"~(<text x="{}" y="20" font-size="13">hemisphere, {} random b: transfer stitches vs the metric's estimate (Pearson r = {:.2f})</text>)~",
                   L, trials.size(), r)
    << "\n";
  for (int k = 0; k <= 5; ++k) {
    const double xv = xmax * k / 5, yv = ymax * k / 5;
    s << fmt::format(R"~(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#ddd"/>)~", L, Y(yv), L + pw, Y(yv)) << "\n"
      << fmt::format(R"~(<text x="{:.1f}" y="{:.1f}" text-anchor="end">{:g}</text>)~", L - 6, Y(yv) + 4, yv) << "\n"
      << fmt::format(R"~(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{:g}</text>)~", X(xv), T + ph + 16, xv) << "\n";
  }
  s << fmt::format(R"~(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#444"/>)~", L, T, pw, ph) << "\n"
    << fmt::format(R"~(<text x="{:.1f}" y="{:.1f}" text-anchor="middle">estimated transfer stitches 3/2 I(f) / sw</text>)~", L + pw / 2, H - 10.0) << "\n"
    << fmt::format(R"~(<text x="14" y="{:.1f}" transform="rotate(-90 14 {:.1f})" text-anchor="middle">transfer stitches (increases + decreases)</text>)~",
                   T + ph / 2, T + ph / 2)
    << "\n";
  // Least-squares line, clipped to the plot.
  const double x0 = 0.0, x1 = xmax;
  const double y0 = std::clamp(offset + slope * x0, 0.0, ymax), y1 = std::clamp(offset + slope * x1, 0.0, ymax);
  s << fmt::format(R"~(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#c0392b" stroke-width="1.5" stroke-dasharray="6 4"/>)~",
                   X(slope != 0 ? (y0 - offset) / slope : x0), Y(y0), X(slope != 0 ? (y1 - offset) / slope : x1), Y(y1))
    << "\n";
  for (const Trial& t : trials) {
    if (t.transfers < 0) continue;
    s << fmt::format(R"~(<circle cx="{:.1f}" cy="{:.1f}" r="4" fill="{}" stroke="#1f5fa8"/>)~", X(t.estimate), Y(t.transfers),
                     t.knittable ? "#1f5fa8" : "white")
      << "\n";
  }
  const double ly = T + 16;
  s << fmt::format(R"~(<circle cx="{:.1f}" cy="{:.1f}" r="4" fill="#1f5fa8"/><text x="{:.1f}" y="{:.1f}">knittable</text>)~", L + 14, ly, L + 22, ly + 4)
    << fmt::format(R"~(<circle cx="{:.1f}" cy="{:.1f}" r="4" fill="white" stroke="#1f5fa8"/><text x="{:.1f}" y="{:.1f}">not knittable</text>)~", L + 104, ly, L + 112, ly + 4)
    << fmt::format(R"~(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="#c0392b" stroke-dasharray="6 4"/><text x="{:.1f}" y="{:.1f}">least squares: {:.1f} + {:.2f} x</text>)~",
                   L + 214, ly, L + 238, ly, L + 244, ly + 4, offset, slope)
    << "\n</svg>\n";
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace knitforge;
  const std::string outdir = argc > 1 ? argv[1] : "out/fig316";
  const int n = argc > 2 ? std::atoi(argv[2]) : 60;
  const unsigned seed = argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 16u;
  if (n < 2 || n > 1000) {
    std::fprintf(stderr, "example_06: N must be 2..1000\n");
    return 2;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const TriMesh mesh = make_shape("hemisphere", kDefaultShapeEdgeLength);
  HarmonicFieldSolver solver(mesh);
  ShortColumnOptions opt;  // stitch 3.5 x 2.8 mm, as the CLI's default
  opt.evaluate = false;
  std::string stage;
  opt.progress = [&](const std::string& s) { stage = s; };

  std::vector<Trial> trials;
  std::printf("  #  b0     b1     b2     b3     estimate transfers knittable  failure\n");
  for (int i = 0; i < n; ++i) {
    Trial t;
    t.b = boundary_from_unit(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)));
    stage = "harmonic field";
    try {
      const HarmonicField h = solver.solve(t.b);
      const ShortColumnDesign d = design_short_columns(mesh, h.value, opt);
      t.estimate = d.metric.transfer_estimate(opt.params.stitch_width);
      t.transfers = d.counts.transfers();
      t.knittable = d.knittable();
      t.stitches = d.counts.stitches;
      t.stitches_vs_area = d.counts.stitches / (d.surface_area / (opt.params.stitch_width * opt.params.stitch_height)) - 1.0;
      t.uncovered = d.wales.uncovered_area;
      t.joined = d.wales.joined_arcs;
      t.tiny = d.wales.tiny_arcs;
      t.sampleless = d.wales.sampleless_regions;
      if (!t.knittable) {
        const std::string m = broken_rules(d.map_check, "map"), s = broken_rules(d.mesh_check, "mesh");
        t.failure = m + (m.empty() || s.empty() ? "" : ", ") + s;
      }
    } catch (const Error& e) {
      std::string what = e.what();
      if (what.size() > 90) what = what.substr(0, 87) + "...";
      t.failure = stage + ": " + what;
    }
    std::printf("%3d  %.3f  %.3f  %.3f  %.3f  %8.1f %9d %9s  %s\n", i, t.b[0], t.b[1], t.b[2], t.b[3], t.estimate,
                t.transfers, t.knittable ? "yes" : "no", t.failure.c_str());
    std::fflush(stdout);
    trials.push_back(t);
  }

  // Statistics over the designed b.
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  int m = 0, knittable = 0;
  std::map<std::string, int> failures;
  for (const Trial& t : trials) {
    knittable += t.knittable;
    if (!t.knittable) {
      // Group by the first rule (without its count) / the stage.
      std::string key = t.failure.substr(0, t.failure.find_first_of(",:"));
      key = key.substr(0, key.find(" x"));
      ++failures[key];
    }
    if (t.transfers < 0) continue;
    ++m;
    const double x = t.estimate, y = t.transfers;
    sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
  }
  double r = 0, slope = 0, offset = 0;
  if (m >= 2) {
    const double cxx = sxx - sx * sx / m, cyy = syy - sy * sy / m, cxy = sxy - sx * sy / m;
    r = cxx > 0 && cyy > 0 ? cxy / std::sqrt(cxx * cyy) : 0.0;
    slope = cxx > 0 ? cxy / cxx : 0.0;
    offset = (sy - slope * sx) / m;
  }
  std::vector<int> tr;
  for (const Trial& t : trials)
    if (t.transfers >= 0) tr.push_back(t.transfers);
  std::sort(tr.begin(), tr.end());
  std::printf("designed %d of %d, knittable %d (%.0f %%)\n", m, n, knittable, 100.0 * knittable / n);
  for (const auto& [k, c] : failures) std::printf("  not knittable: %d x %s\n", c, k.c_str());
  if (!tr.empty())
    std::printf("transfers %d-%d, median %d; Pearson r = %.2f; least squares transfers = %.1f + %.2f x estimate\n",
                tr.front(), tr.back(), tr[tr.size() / 2], r, offset, slope);
  {
    std::vector<double> excess, uncovered;
    int joined = 0, tiny = 0, sampleless = 0;
    for (const Trial& t : trials) {
      if (t.transfers < 0) continue;
      excess.push_back(100.0 * t.stitches_vs_area);
      uncovered.push_back(t.uncovered);
      joined += t.joined, tiny += t.tiny, sampleless += t.sampleless;
    }
    std::sort(excess.begin(), excess.end());
    std::sort(uncovered.begin(), uncovered.end());
    if (!excess.empty())
      std::printf("stitches vs area: median %+.1f %% (%+.1f to %+.1f); uncovered area median %.1f mm^2, max %.1f mm^2; "
                  "wale pieces joined along the rim %d, tiny pieces %d, regions without front samples %d\n",
                  excess[excess.size() / 2], excess.front(), excess.back(), uncovered[uncovered.size() / 2], uncovered.back(),
                  joined, tiny, sampleless);
  }

  std::filesystem::create_directories(outdir);
  {
    std::ofstream csv(outdir + "/metric_vs_transfers.csv");
    csv << "b0,b1,b2,b3,estimate,transfers,knittable,stitches,stitches_vs_area,uncovered_mm2,failure\n";
    for (const Trial& t : trials)
      csv << fmt::format("{:.6f},{:.6f},{:.6f},{:.6f},{:.3f},{},{},{},{:.4f},{:.2f},\"{}\"\n", t.b[0], t.b[1], t.b[2], t.b[3],
                         t.estimate, t.transfers, t.knittable ? 1 : 0, t.stitches, t.stitches_vs_area, t.uncovered, t.failure);
  }
  std::ofstream(outdir + "/metric_vs_transfers.svg") << scatter_svg(trials, slope, offset, r);
  std::printf("-> %s/metric_vs_transfers.svg, %s/metric_vs_transfers.csv\n", outdir.c_str(), outdir.c_str());
  return 0;
}
