// `prs compare BEFORE AFTER`: two runs of a controller on the same scenes, before and after a
// change, side by side (docs/search.md, "Before and after a change"): the outcome counts, the
// scenes fixed and broken with their regenerate commands, and McNemar's exact test. Markdown
// on stdout or in -o OUT.md; --json prints one JSON object instead.
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "output/line_writer.h"
#include "search/compare.h"

namespace prs::cli {
namespace {

struct CompareArgs {
  std::string before, after;
  std::string output;  // empty: stdout
  bool json = false;
};

int RunCompare(const CompareArgs& args) {
  const auto before_lines = ReadLines(args.before);
  if (!before_lines) return kExitScenarioError;
  const auto after_lines = ReadLines(args.after);
  if (!after_lines) return kExitScenarioError;
  try {
    const search::PairedComparison comparison = search::ComparePairedRuns(
        search::ParseReportRecords(*before_lines, args.before), args.before,
        search::ParseReportRecords(*after_lines, args.after), args.after);
    const std::string text = args.json ? search::FormatComparisonJson(comparison) + "\n"
                                       : search::FormatComparisonMarkdown(comparison);
    if (args.output.empty()) {
      std::cout << text << std::flush;
      return kExitSuccess;
    }
    output::WriteFileAtomically(args.output, text);
    PrintNote(fmt::format("{} scenes compared ({} fixed, {} broken, McNemar p = {:.4g}); written "
                          "to {}",
                          comparison.scenes.size(), comparison.fixed.size(),
                          comparison.broke.size(), comparison.mcnemar_p, args.output));
    return kExitSuccess;
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
}

}  // namespace

CommandRunner ConfigureCompareCommand(CLI::App& command) {
  auto args = std::make_shared<CompareArgs>();
  command.add_option("BEFORE", args->before, "episode records of the run before the change")
      ->required()
      ->check(NonEmptyPath());
  command.add_option("AFTER", args->after, "episode records of the same scenes after it")
      ->required()
      ->check(NonEmptyPath());
  command.add_option("-o,--output", args->output, "write the comparison to OUT instead of stdout")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  command.add_flag("--json", args->json, "one JSON object instead of Markdown");
  return [args] { return RunCompare(*args); };
}

}  // namespace prs::cli
