// What `prs test` and `prs search` share: choosing the controller (--controller NAME or
// --exec CMD, with a did-you-mean), the scenario words of regenerate commands, --timeout's
// check, and the outcome table.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "cli/common.h"
#include "harness/harness.h"

namespace prs::cli {

/// --controller NAME / --exec CMD / --timeout S.
struct ControllerArgs {
  std::string controller;
  std::string exec;
  double timeout_s = 60;
};

/// Adds --controller, --exec (excluding each other) and --timeout to `command`.
void AddControllerOptions(CLI::App& command, ControllerArgs& args);

/// The built-in controllers' names, comma-separated.
std::string ListControllerNames();

/// The factory for --controller NAME or --exec CMD; nullopt after printing a usage error.
std::optional<harness::ControllerFactory> ChooseController(const ControllerArgs& args,
                                                           const std::atomic<bool>& cancel);

/// What `prs sample` needs to rewrite one of these scenes: FILE, -I, -p, --naive.
std::vector<std::string> MakeScenarioWords(const ScenarioArgs& scenario,
                                           const SamplingArgs& sampling);

/// outcome / count / share, with a total row (the paper's Table III).
std::string FormatOutcomeTable(const std::vector<harness::EpisodeRecord>& records);

}  // namespace prs::cli
