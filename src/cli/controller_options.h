// What `prs test` and `prs search` share: choosing the controller (--controller NAME or
// --exec CMD, with a did-you-mean), the scenario words of regenerate commands, --timeout's
// check, and the outcome table.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/common.h"
#include "harness/harness.h"
#include "output/line_writer.h"

namespace prs::cli {

/// --controller NAME / --exec CMD / --timeout S / --persistent / --startup-timeout S /
/// --perception CMD.
struct ControllerArgs {
  std::string controller;
  std::string exec;
  double timeout_s = 60;
  bool persistent = false;
  double startup_timeout_s = 120;
  std::string perception;  // --perception CMD: table-cube's learned perception
};

/// Adds --controller, --exec (excluding each other), --timeout, --persistent (needing --exec),
/// --startup-timeout and --perception (excluding --exec) to `command`.
void AddControllerOptions(CLI::App& command, ControllerArgs& args);

/// The built-in controllers' names, comma-separated.
std::string ListControllerNames();

/// The factory for --controller NAME or --exec CMD; nullopt after printing a usage error.
std::optional<harness::ControllerFactory> ChooseController(const ControllerArgs& args,
                                                           const std::atomic<bool>& cancel);

/// What `prs sample` needs to rewrite one of these scenes: FILE, -I, -p, --naive.
std::vector<std::string> MakeScenarioWords(const ScenarioArgs& scenario,
                                           const SamplingArgs& sampling);

/// Opens -o OUT (when given) as *records and creates --save-failures DIR (when given). Returns
/// false after printing why one of them cannot be made.
bool OpenEpisodeOutputs(const std::string& output, const std::string& save_failures_dir,
                        std::unique_ptr<output::LineWriter>* records);

/// After a run stopped early: "the 12 records so far are in OUT.partial" once they are
/// flushed there, or that no episode finished, so no record file was left.
std::string DescribeRecordsSoFar(output::LineWriter& records);

/// outcome / count / share, with a total row (the paper's Table III).
std::string FormatOutcomeTable(const std::vector<harness::EpisodeRecord>& records);

}  // namespace prs::cli
