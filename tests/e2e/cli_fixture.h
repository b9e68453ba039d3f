#pragma once
// Test fixture for end-to-end runs of the knitforge program: a fresh
// temporary directory per test, and run() capturing exit code and output.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace knitforge_e2e {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// The data a report page embeds (report_data(), docs/report.md): the JSON
/// of its `knitforge-data` script element; null when there is none.
inline nlohmann::json report_page_data(const fs::path& html_file) {
  const std::string html = slurp(html_file);
  const std::string open = R"(<script type="application/json" id="knitforge-data">)";
  const size_t begin = html.find(open);
  if (begin == std::string::npos) return nullptr;
  const size_t from = begin + open.size();
  return nlohmann::json::parse(html.substr(from, html.find("</script>", from) - from));
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    // The process id keeps two runs of one test apart (two checkouts tested
    // at once on one machine shared /tmp/knitforge_e2e_<test> and failed).
    dir_ = fs::temp_directory_path() /
           ("knitforge_e2e_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Runs the CLI with `args` (in directory `cwd` when given).
  CliRun run(const std::string& args, const std::string& cwd = "") {
    const std::string out = (dir_ / "stdout.txt").string(), err = (dir_ / "stderr.txt").string();
    const std::string cmd = (cwd.empty() ? std::string() : "cd '" + cwd + "' && ") + std::string(KNITFORGE_CLI) +
                            " " + args + " >" + out + " 2>" + err + " </dev/null";
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // knitout MAP_CSV --machine M -o PROGRAM, then simulate PROGRAM --against
  // MAP_CSV: the program is written and the virtual machine says it knits
  // exactly the map.
  void expect_knitted_as_designed(const std::string& map_csv, const std::string& program, const std::string& machine) {
    CliRun r = run("knitout " + map_csv + " --machine " + machine + " -o " + program);
    ASSERT_EQ(r.code, 0) << r.err;
    r = run("simulate " + program + " --machine " + machine + " --against " + map_csv);
    EXPECT_EQ(r.code, 0) << r.err << r.out;
    EXPECT_NE((r.out + r.err).find("MATCHES the map"), std::string::npos) << r.err << r.out;
  }

  fs::path dir_;
};

}  // namespace knitforge_e2e
