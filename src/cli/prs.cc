// The `prs` command: `sample` writes scenes as JSON Lines, `check` compiles and outlines a
// scenario, `stats` measures sampling. Data on stdout; diagnostics, summaries and progress on
// stderr. Exit codes: 0 success, 1 scenario error, 2 usage error, 3 sampling failure
// (docs/cli.md).
#include <CLI/CLI.hpp>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/common.h"

namespace prs::cli {

const std::vector<Command>& CommandTable() {
  static const std::vector<Command> kCommands = {
      {"sample", "sample scenes and write them as JSON Lines", ConfigureSampleCommand},
      {"check", "compile a scenario and outline its objects, classes and randomness",
       ConfigureCheckCommand},
      {"stats", "sample scenes and report acceptance, rejections and speed", ConfigureStatsCommand},
      {"view", "look at scenes in a local web viewer (or write one HTML file)", ConfigureViewCommand},
      {"export", "write scenes as MJCF, URDF, SDF, USD or glTF files", ConfigureExportCommand},
      {"render", "draw scenes as PNG pictures (offscreen, no display needed)", ConfigureRenderCommand},
      {"dataset", "labelled pictures of scenes for learning: BOP and COCO (exact masks, poses)",
       ConfigureDatasetCommand},
      {"test", "run a controller in sampled scenes, tabulate outcomes", ConfigureTestCommand},
      {"search", "search for scenes where a controller fails (ce, anneal)", ConfigureSearchCommand},
      {"estimate", "how often a controller fails, with a 95 % interval (importance sampling)",
       ConfigureEstimateCommand},
      {"report", "a failure report from episode records: what separates failures", ConfigureReportCommand},
      {"compare", "two runs of the same scenes, before and after a change: fixed, broken, McNemar",
       ConfigureCompareCommand},
      {"campaign", "a run cut into shards for many machines: init, run-shard, status, merge",
       ConfigureCampaignCommand},
  };
  return kCommands;
}

namespace {

std::string ListCommandNames() {
  std::string list;
  for (const Command& command : CommandTable())
    list += (list.empty() ? "" : ", ") + std::string(command.name);
  return list;
}

// `prs` alone, or `prs sampel ...`: returns the error to print, or nullopt when the first
// argument is a command or an option (left to CLI11).
std::optional<std::string> DiagnoseMissingCommand(int argc, char** argv) {
  if (argc < 2) return "no command given (commands: " + ListCommandNames() + ")";
  if (argv[1][0] == '-') return std::nullopt;
  const std::string word = argv[1];
  std::vector<std::string> names;
  for (const Command& command : CommandTable()) {
    if (word == command.name) return std::nullopt;
    names.push_back(command.name);
  }
  const std::string suggestion = lang::SuggestClosest(word, names);
  if (!suggestion.empty())
    return "unknown command '" + word + "'; did you mean '" + suggestion + "'?";
  return "unknown command '" + word + "' (commands: " + ListCommandNames() + ")";
}

int ReportParseError(const CLI::App& app, const CLI::ParseError& error) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    return app.exit(error);  // --help or --version: printed on stdout
  }
  PrintError(error.what());
  std::cerr << "run 'prs --help' or 'prs COMMAND --help' for usage\n";
  return kExitUsage;
}

int RunCommandLine(int argc, char** argv) {
  CLI::App app{"prs: sample scenes from ProbRobScene programs", "prs"};
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", "prs " PRS_VERSION);
  app.footer(
      "Exit codes: 0 success, 1 scenario error, 2 usage error, 3 sampling failure, 128+N "
      "stopped by signal N.\nSee docs/cli.md.");
  std::vector<std::pair<CLI::App*, CommandRunner>> runners;
  for (const Command& command : CommandTable()) {
    CLI::App* subcommand = app.add_subcommand(command.name, command.help);
    runners.emplace_back(subcommand, command.configure(*subcommand));
  }
  if (const auto missing = DiagnoseMissingCommand(argc, argv)) {
    PrintError(*missing);
    std::cerr << "run 'prs --help' for usage\n";
    return kExitUsage;
  }
  for (const auto& [subcommand, run] : runners) {
    if (argv[1] != subcommand->get_name()) continue;
    if (const auto spaced = DiagnoseSpacedFlagValue(*subcommand, {argv + 2, argv + argc})) {
      PrintError(*spaced);
      std::cerr << "run 'prs " << subcommand->get_name() << " --help' for usage\n";
      return kExitUsage;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return ReportParseError(app, error);
  }
  for (auto& [subcommand, run] : runners) {
    if (subcommand->parsed()) return run();
  }
  return kExitUsage;  // unreachable: require_subcommand(1, 1)
}

}  // namespace
}  // namespace prs::cli

int main(int argc, char** argv) {
  // Every user error is reported by the commands; what reaches here is a bug, reported as one
  // line instead of an abort.
  try {
    return prs::cli::RunCommandLine(argc, argv);
  } catch (const std::exception& error) {
    prs::cli::PrintError(std::string("internal error: ") + error.what());
  } catch (...) {
    prs::cli::PrintError("internal error: unknown exception");
  }
  return prs::cli::kExitScenarioError;
}
