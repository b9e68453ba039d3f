// knitforge report: the self-contained report page (report.html) of a design
// output directory (docs/report.md).
#include <filesystem>

#include <fmt/core.h>

#include "cli_common.h"
#include "knitforge/report/report_html.h"

namespace knitforge::cli {

void add_report_command(CLI::App& app, Action& action) {
  auto* cmd = app.add_subcommand(
      "report",
      "Write OUTDIR/report.html: 3D view, knitting map, metrics and knitout statistics of a design run");
  struct Opts {
    std::string outdir, output, title;
    double resolution = 0.01;
    bool no_simulate = false;
  };
  auto o = std::make_shared<Opts>();
  cmd->add_option("outdir", o->outdir, "Output directory of a design command")->required();
  cmd->add_option("-o,--output", o->output, "Page to write (default OUTDIR/report.html)");
  cmd->add_option("--title", o->title, "Page title (default: the directory's name)");
  cmd->add_option("--resolution", o->resolution, "Coordinates are rounded to this length (mm)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_flag("--no-simulate", o->no_simulate, "Do not run the knitout simulator for the statistics");
  cmd->callback([=, &action] {
    action = [=]() -> int {
      if (!o->output.empty()) check_output_file("-o", o->output, {".html", ".htm"});
      ReportHtmlOptions opt;
      opt.output = o->output;
      opt.title = o->title;
      opt.quantum_mm = o->resolution;
      opt.simulate_knitout = !o->no_simulate;
      write_report_html(o->outdir, opt);
      const std::string out =
          o->output.empty() ? (std::filesystem::path(o->outdir) / "report.html").string() : o->output;
      note(fmt::format("wrote {} ({} kB); open it in a browser", out,
                       (std::filesystem::file_size(out) + 1023) / 1024));
      return 0;
    };
  });
}

}  // namespace knitforge::cli
