// `prs report`: a failure report from episode records (prs test -o, prs search -o): what
// separates failures from successes, a depth-2 tree, failure modes with representatives, and
// error tables by feature and scene coordinate (docs/search.md, "Failure reports"). Markdown
// on stdout, or in -o OUT.md with a scatter plot beside it (OUT.svg). The report's links (the
// plot, the failures' saved scenes and pictures) are relative to the report's own folder.
#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <system_error>

#include "cli/commands.h"
#include "cli/common.h"
#include "output/line_writer.h"
#include "search/report.h"

namespace prs::cli {
namespace {

namespace fs = std::filesystem;

struct ReportArgs {
  std::string results;
  std::string output;  // empty or "-": stdout
};

// The extension of the path's file name, lower case ("" when there is none).
std::string LowerExtension(const std::string& path) {
  const size_t slash = path.rfind('/');
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string extension = path.substr(dot);
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

// OUT.md -> OUT.svg (any other name: NAME.svg).
std::string SvgPathFor(const std::string& output) {
  const size_t slash = output.rfind('/');
  const size_t dot = output.rfind('.');
  const bool has_extension =
      dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_extension ? output.substr(0, dot) : output) + ".svg";
}

// -o names the Markdown report; the plot goes beside it as NAME.svg, so a .svg report would be
// overwritten by its own plot (or the plot by the report).
CLI::Validator NotAnSvgPath() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (LowerExtension(text) != ".svg") return "";
        return fmt::format(
            "'{}' is where the plot would go: the report is Markdown and its plot is written "
            "beside it as NAME.svg; give the report a .md name (-o {}.md writes {}.md and {})",
            text, text.substr(0, text.size() - 4), text.substr(0, text.size() - 4),
            SvgPathFor(text));
      },
      "");
}

// When the folder the report goes in is missing or not a folder: the error to print, naming the
// folder as the user gave it (not the PATH.partial the writer would fail to create). Else "".
std::string CheckOutputFolder(const std::string& output) {
  const fs::path folder = fs::path(output).parent_path();
  if (folder.empty()) return "";
  std::error_code error;
  const fs::file_status status = fs::status(folder, error);
  if (fs::is_directory(status)) return "";
  // Unreadable (no permission): the writer says why.
  if (error && error != std::errc::no_such_file_or_directory) return "";
  if (fs::exists(status)) {
    return fmt::format("cannot write the report {}: '{}' is not a folder", output, folder.string());
  }
  return fmt::format(
      "cannot write the report {}: the folder '{}' does not exist; create it first (mkdir -p "
      "'{}') or give -o a path in an existing folder",
      output, folder.string(), folder.string());
}

// A record's saved scene as a path from `report_folder` (both folders absolute). prs test
// records the path it wrote, relative to the folder it ran in: most often the one prs report
// runs in, else the results file's (prs test run there, its results read from elsewhere). The
// first of the two where the scene exists (the first when neither does); an absolute path
// stays where it is.
std::string LinkSavedScene(const std::string& saved_scene, const fs::path& results_folder,
                           const fs::path& report_folder) {
  fs::path scene = saved_scene;
  if (scene.is_relative()) {
    std::error_code error;
    const fs::path from_here = fs::absolute(scene, error);
    const fs::path from_results = results_folder / scene;
    scene =
        !fs::exists(from_here, error) && fs::exists(from_results, error) ? from_results : from_here;
  }
  std::error_code error;
  const fs::path canonical_scene = fs::weakly_canonical(scene, error);
  if (!error) scene = canonical_scene;
  const fs::path link = scene.lexically_relative(report_folder);
  return link.empty() ? scene.generic_string() : link.generic_string();
}

// The folder of `path` (a file), absolute and without symbolic links.
fs::path CanonicalFolderOf(const std::string& path) {
  std::error_code error;
  fs::path folder = fs::absolute(fs::path(path), error).parent_path();
  const fs::path canonical = fs::weakly_canonical(folder, error);
  return error ? folder : canonical;
}

int RunReport(const ReportArgs& args) {
  const bool to_stdout = args.output.empty() || args.output == "-";
  if (!to_stdout) {
    if (const std::string error = CheckOutputFolder(args.output); !error.empty()) {
      PrintError(error);
      return kExitScenarioError;
    }
  }
  const auto lines = ReadLines(args.results);
  if (!lines) return kExitScenarioError;
  try {
    std::vector<search::ReportRecord> records = search::ParseReportRecords(*lines, args.results);
    // The links from the report's folder (the working directory's for stdout).
    const fs::path report_folder =
        to_stdout ? CanonicalFolderOf("./report.md") : CanonicalFolderOf(args.output);
    const fs::path results_folder = CanonicalFolderOf(args.results);
    for (search::ReportRecord& record : records) {
      if (record.saved_scene.empty()) continue;
      record.saved_scene = LinkSavedScene(record.saved_scene, results_folder, report_folder);
    }
    search::ReportOptions options;
    options.title = args.results;
    if (!to_stdout) options.svg_path = SvgPathFor(args.output);
    std::string svg;
    const std::string markdown = search::FormatFailureReport(records, options, &svg);
    if (to_stdout) {
      std::cout << markdown << std::flush;
      return kExitSuccess;
    }
    if (!svg.empty()) output::WriteFileAtomically(options.svg_path, svg);
    output::WriteFileAtomically(args.output, markdown);
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
                  "write the Markdown report to OUT (and a scatter plot beside it, OUT.svg; "
                  "OUT itself cannot be a .svg file); - or no -o: stdout")
      ->type_name("OUT")
      ->check(NonEmptyPath())
      ->check(NotAnSvgPath());
  return [args] { return RunReport(*args); };
}

}  // namespace prs::cli
