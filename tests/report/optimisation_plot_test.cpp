#include "knitforge/report/optimisation_plot.h"

#include <string>

#include <gtest/gtest.h>

#include "knitforge/util/errors.h"

namespace knitforge {
namespace {

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

BoundaryOptimisation history() {
  BoundaryOptimisation o;
  const double values[] = {30.0, 20.0, 25.0, 10.0, 12.0};
  double best = 1e300;
  for (int i = 0; i < 5; ++i) {
    BoundaryEvaluation e;
    e.evaluated = e.suggested = {0.1 * i, 0.1 * i + 0.05, 0.6, 0.7};
    e.value = e.penalised = values[i];
    e.initial = i < 2;
    e.projected = i == 4;
    best = std::min(best, e.value);
    e.best = best;
    o.history.push_back(e);
  }
  o.best = o.history[3].evaluated;
  o.best_value = 10.0;
  o.alternatives = {3, 1};
  return o;
}

TEST(OptimisationPlot, OneMarkPerEvaluationAndTheAlternativesNumbered) {
  const BoundaryOptimisation o = history();
  const std::string svg = optimisation_plot_svg(o);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  // 5 evaluations + 2 legend marks; one hollow (projected) plus the legend's.
  EXPECT_EQ(count(svg, "<circle"), 7u);
  EXPECT_EQ(count(svg, R"(fill="white" stroke="#1f5fa8")"), 2u);
  EXPECT_EQ(count(svg, R"(font-weight="bold">)"), 2u);
  EXPECT_THROW(optimisation_plot_svg(BoundaryOptimisation{}), InvalidInput);
  EXPECT_THROW(optimisation_plot_svg(o, 100, 100), InvalidInput);
}

TEST(OptimisationPlot, JsonHoldsTheHistoryAndTheBest) {
  const nlohmann::json j = optimisation_json(history());
  ASSERT_EQ(j["evaluations"].size(), 5u);
  EXPECT_DOUBLE_EQ(j["evaluations"][3]["best_so_far"].get<double>(), 10.0);
  EXPECT_TRUE(j["evaluations"][4]["projected"].get<bool>());
  EXPECT_DOUBLE_EQ(j["best"]["estimated_transfers"].get<double>(), 10.0);
  EXPECT_EQ(j["alternatives"].size(), 2u);
}

}  // namespace
}  // namespace knitforge
