// `prs report`: a failure report from episode records (prs test -o, prs search -o): what
// separates failures from successes, a depth-2 tree, failure modes with representatives, and
// error tables by feature and scene coordinate (docs/search.md, "Failure reports"). Markdown
// on stdout, or in -o OUT.md with a scatter plot beside it (OUT.svg).
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/common.h"
#include "search/report.h"

namespace prs::cli {
namespace {

struct ReportArgs {
  std::string results;
  std::string output;  // empty: stdout
};

// OUT.md -> OUT.svg (any other name: NAME.svg).
std::string SvgPathFor(const std::string& output) {
  const size_t slash = output.rfind('/');
  const size_t dot = output.rfind('.');
  const bool has_extension =
      dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_extension ? output.substr(0, dot) : output) + ".svg";
}

int RunReport(const ReportArgs& args) {
  const auto lines = ReadLines(args.results);
  if (!lines) return kExitScenarioError;
  try {
    const std::vector<search::ReportRecord> records =
        search::ParseReportRecords(*lines, args.results);
    search::ReportOptions options;
    options.title = args.results;
    if (!args.output.empty()) options.svg_path = SvgPathFor(args.output);
    std::string svg;
    const std::string markdown = search::FormatFailureReport(records, options, &svg);
    if (args.output.empty()) {
      std::cout << markdown << std::flush;
      return kExitSuccess;
    }
    if (!svg.empty()) WriteTextFile(options.svg_path, svg);
    WriteTextFile(args.output, markdown);
    PrintNote(fmt::format("report of {} written to {}{}", FormatCount(records.size(), "episode"),
                          args.output, svg.empty() ? "" : " (plot: " + options.svg_path + ")"));
    return kExitSuccess;
  } catch (const std::exception& error) {
    PrintError(error.what());
    return kExitScenarioError;
  }
}

}  // namespace

CommandRunner ConfigureReportCommand(CLI::App& command) {
  auto args = std::make_shared<ReportArgs>();
  command.add_option("RESULTS", args->results, "episode records (prs test -o, prs search -o)")
      ->required()
      ->check(NonEmptyPath());
  command
      .add_option("-o,--output", args->output,
                  "write the Markdown report to OUT (and a scatter plot beside it, OUT.svg)")
      ->type_name("OUT")
      ->check(NonEmptyPath());
  return [args] { return RunReport(*args); };
}

}  // namespace prs::cli
