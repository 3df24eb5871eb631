// The table of `prs` subcommands: each entry names a command, says what it does, and adds its
// options to a CLI11 subcommand; main() builds the command line, its help and its "did you
// mean" from this table alone.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace prs::cli {

/// Runs a parsed command and returns the process exit code.
using CommandRunner = std::function<int()>;

struct Command {
  const char* name;
  const char* help;
  /// Adds the command's options to `command` (their values live in the returned runner).
  CommandRunner (*configure)(CLI::App& command);
};

/// Every subcommand, in the order `prs --help` lists them.
const std::vector<Command>& CommandTable();

CommandRunner ConfigureSampleCommand(CLI::App& command);
CommandRunner ConfigureCheckCommand(CLI::App& command);
CommandRunner ConfigureStatsCommand(CLI::App& command);
CommandRunner ConfigureViewCommand(CLI::App& command);
CommandRunner ConfigureExportCommand(CLI::App& command);
CommandRunner ConfigureRenderCommand(CLI::App& command);
CommandRunner ConfigureDatasetCommand(CLI::App& command);
CommandRunner ConfigureTestCommand(CLI::App& command);
CommandRunner ConfigureSearchCommand(CLI::App& command);
CommandRunner ConfigureEstimateCommand(CLI::App& command);
CommandRunner ConfigureReportCommand(CLI::App& command);
CommandRunner ConfigureCompareCommand(CLI::App& command);
CommandRunner ConfigureCampaignCommand(CLI::App& command);

}  // namespace prs::cli
