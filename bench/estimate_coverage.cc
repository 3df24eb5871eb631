// How often prs estimate's 95 % intervals cover the truth on failure shapes of exact
// probability (src/search/test/failure_shapes.h), over many seeds: per shape, the intervals
// covering, the runs that said "unreliable", the median relative error, the runs within ±20 %
// of the truth (reliable or not: i.i.d. sampling needs (1.96 / 0.2)^2 (1 - p) / p episodes for
// 95 in 100 of them), and the i.i.d.
// episodes the estimate is worth, both as reported (p (1 - p) / variance, median) and as
// measured (p (1 - p) / mean squared error over the seeds). docs/search.md reports its output.
// Run: ./build/bench/estimate_coverage [--seeds 100] [--first 1001] [--budget 2000] [SHAPE...]
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "harness/registry.h"
#include "search/estimate.h"
#include "search/test/failure_shapes.h"

namespace {

using prs::search::testing_shapes::FailureShape;

double Median(std::vector<double> x) {
  if (x.empty()) return 0;
  std::sort(x.begin(), x.end());
  return (x[(x.size() - 1) / 2] + x[x.size() / 2]) / 2;
}

void MeasureShape(const prs::lang::CompiledProgram& program, const FailureShape& shape,
                  const prs::harness::ControllerFactory& factory, int seeds, int first,
                  int64_t budget) {
  int covered = 0, unreliable = 0, missed_flagged = 0, within = 0;
  std::vector<double> errors, reported_iid;
  double squared = 0;
  for (int seed = first; seed < first + seeds; ++seed) {
    prs::search::EstimateOptions options;
    options.budget = budget;
    options.run.seed = uint64_t(seed);
    options.run.threads = 2;
    const prs::search::EstimateSummary summary =
        prs::search::RunEstimate(program, factory, options);
    double p = 0, low = 0, high = summary.estimate.upper_bound, iid = 0;
    for (const prs::search::OutcomeEstimate& o : summary.estimate.outcomes) {
      if (o.outcome == shape.name) p = o.p, low = o.ci_low, high = o.ci_high, iid = o.iid_episodes;
    }
    unreliable += !summary.estimate.reliable;
    // A run flagged unreliable whose interval would have missed: the flag did its job.
    missed_flagged += !summary.estimate.reliable && !(low <= shape.truth && shape.truth <= high);
    covered += summary.estimate.reliable && low <= shape.truth && shape.truth <= high;
    errors.push_back(std::abs(p - shape.truth) / shape.truth);
    within += errors.back() <= 0.2;
    reported_iid.push_back(iid);
    squared += (p - shape.truth) * (p - shape.truth) / seeds;
  }
  const double measured_iid = shape.truth * (1 - shape.truth) / squared;
  std::cout << fmt::format(
      "| {} | {:.3g} % | {} ({}–{}) | {} | {} ({} would have missed) | {:.0f} % | {} | {:.0f} | "
      "{:.0f} |\n",
      shape.name, 100 * shape.truth, seeds, first, first + seeds - 1, covered, unreliable,
      missed_flagged, 100 * Median(errors), within, Median(reported_iid), measured_iid);
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 100, first = 1001;
  int64_t budget = 2000;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--seeds" || arg == "--first" || arg == "--budget") && i + 1 < argc) {
      const long value = std::strtol(argv[++i], nullptr, 10);
      if (arg == "--seeds") seeds = int(value);
      if (arg == "--first") first = int(value);
      if (arg == "--budget") budget = value;
    } else {
      names.push_back(arg);
    }
  }
  const auto program = prs::search::testing_shapes::CompileTwoPoints();
  std::cout << fmt::format("budget {} episodes a run\n\n", budget)
            << "| shape | truth | seeds | covering | unreliable | median error | within ±20 % | "
               "i.i.d. episodes as reported (median) | i.i.d. episodes for the measured error |\n"
               "|---|---|---|---|---|---|---|---|---|\n";
  const auto wanted = [&](const std::string& name) {
    return names.empty() || std::find(names.begin(), names.end(), name) != names.end();
  };
  for (const FailureShape& shape : prs::search::testing_shapes::ListFailureShapes()) {
    if (!wanted(shape.name)) continue;
    MeasureShape(*program, shape, prs::search::testing_shapes::MakeShapeControllerFactory(shape),
                 seeds, first, budget);
  }
  // The shapes the design was chosen on: Table-Cube's planted disks, whose truths come from
  // 2,000,000 i.i.d. episodes each, and 10,000,000 more for the 0.1 % disk (docs/benchmarks.md).
  prs::lang::DiagnosticEngine diagnostics;
  prs::lang::CompileOptions options;
  options.search_path = {std::string(PRS_DEFAULT_SOURCE_DIR) + "/examples"};
  const auto table_cube = prs::lang::CompileFile(
      std::string(PRS_DEFAULT_SOURCE_DIR) + "/examples/table_cube.prs", options, diagnostics);
  const struct {
    const char* name;
    prs::harness::PlantedFailure failure;
    double truth;
  } planted[] = {
      {"table-cube-1-permille", prs::harness::PlantedOnePermille(), (2131.0 + 10199) / 12e6},
      {"table-cube-1-percent", prs::harness::PlantedOnePercent(), 20338.0 / 2e6}};
  for (const auto& [name, failure, truth] : planted) {
    if (!wanted(name)) continue;
    const FailureShape shape{"planted-failure", truth, nullptr};
    std::cout << name << ": ";
    MeasureShape(
        *table_cube, shape, [failure] { return prs::harness::MakePlantedController(failure); },
        seeds, first, budget);
  }
}
