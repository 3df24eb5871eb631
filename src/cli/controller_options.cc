// Controller choice and the outcome table, shared by `prs test` and `prs search`.
#include "cli/controller_options.h"

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>

#include "cli/text_table.h"
#include "controllers/builtin.h"
#include "harness/registry.h"

namespace prs::cli {

void AddControllerOptions(CLI::App& command, ControllerArgs& args) {
  controllers::RegisterBuiltInControllers();
  CLI::Option* controller = command
                                .add_option("--controller", args.controller,
                                            "a built-in controller (" + ListControllerNames() + ")")
                                ->type_name("NAME");
  CLI::Option* exec =
      command
          .add_option("--exec", args.exec,
                      "your own controller: a shell command run once per scene (docs/harness.md)")
          ->type_name("CMD")
          ->excludes(controller);
  command
      .add_option("--perception", args.perception,
                  "table-cube's learned perception: a worker command shown each sighting's "
                  "picture, answering where the cube is (docs/harness.md, \"Perception workers\")")
      ->type_name("CMD")
      ->excludes(exec);
  command
      .add_option("--timeout", args.timeout_s,
                  "seconds an --exec episode (or a --perception answer) may take")
      ->type_name("S")
      ->check(PositiveNumber("seconds"))
      ->capture_default_str();
  command
      .add_flag("--persistent", args.persistent,
                "start the --exec command once per worker thread and send it one scene per line "
                "(a controller in a simulator that takes seconds to start; docs/harness.md)")
      ->needs(exec);
  command
      .add_option("--startup-timeout", args.startup_timeout_s,
                  "seconds a --persistent or --perception worker may take to send its "
                  "handshake")
      ->type_name("S")
      ->check(PositiveNumber("seconds"))
      ->capture_default_str();
}

std::string ListControllerNames() { return controllers::ListControllerNames(); }

std::optional<harness::ControllerFactory> ChooseController(const ControllerArgs& args,
                                                           const std::atomic<bool>& cancel) {
  if (args.controller.empty() && args.exec.empty()) {
    PrintError("no controller: give --controller NAME (built in: " + ListControllerNames() +
               ") or --exec CMD");
    return std::nullopt;
  }
  const controllers::ControllerChoice choice{args.controller,        args.exec,
                                             args.timeout_s,         args.persistent,
                                             args.startup_timeout_s, args.perception};
  try {
    if (auto factory = controllers::MakeControllerFactory(choice, &cancel)) return factory;
  } catch (const std::invalid_argument& error) {  // options that do not fit together
    PrintError(error.what());
    return std::nullopt;
  }
  std::vector<std::string> names;
  for (const harness::ControllerInfo& info : harness::ListControllers()) names.push_back(info.name);
  const std::string suggestion = lang::SuggestClosest(args.controller, names);
  PrintError("--controller: unknown controller '" + args.controller + "'" +
             (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?") +
             " (controllers: " + ListControllerNames() + ")");
  return std::nullopt;
}

std::string DescribeRecordsSoFar(output::LineWriter& records) {
  try {
    records.Flush();
  } catch (const std::exception& error) {
    return std::string("the records so far could not be written: ") + error.what();
  }
  if (records.lines_written() == 0) {
    return "no episode finished, so no record was written (nor " + records.partial_path() + ")";
  }
  return fmt::format("the {} so far {} in {}", FormatCount(records.lines_written(), "record"),
                     records.lines_written() == 1 ? "is" : "are", records.partial_path());
}

std::vector<std::string> MakeScenarioWords(const ScenarioArgs& scenario,
                                           const SamplingArgs& sampling) {
  std::vector<std::string> words = {scenario.file};
  for (const std::string& dir : scenario.include_dirs) words.insert(words.end(), {"-I", dir});
  for (const std::string& param : scenario.params) words.insert(words.end(), {"-p", param});
  if (sampling.naive) words.push_back("--naive");
  if (sampling.sampler != SamplingArgs{}.sampler)
    words.insert(words.end(), {"--sampler", sampling.sampler});
  // --stable changes which attempt a scene is (unstable ones are rejected): keep it, with
  // tolerances that are not the defaults.
  if (!sampling.stable_s.empty()) {
    words.push_back("--stable=" + sampling.stable_s);
    if (sampling.stable_move_m != SamplingArgs{}.stable_move_m) {
      words.insert(words.end(), {"--stable-move", fmt::format("{}", sampling.stable_move_m)});
    }
    if (sampling.stable_turn_deg != SamplingArgs{}.stable_turn_deg) {
      words.insert(words.end(), {"--stable-turn", fmt::format("{}", sampling.stable_turn_deg)});
    }
  }
  if (!sampling.settle_s.empty()) words.push_back("--settle=" + sampling.settle_s);
  return words;
}

bool OpenEpisodeOutputs(const std::string& output, const std::string& save_failures_dir,
                        std::unique_ptr<output::LineWriter>* records) {
  try {
    if (!output.empty()) *records = std::make_unique<output::LineWriter>(output);
    if (!save_failures_dir.empty()) std::filesystem::create_directories(save_failures_dir);
    return true;
  } catch (const std::exception& error) {
    PrintError(error.what());
    return false;
  }
}

std::string FormatOutcomeTable(const std::vector<harness::EpisodeRecord>& records) {
  TextTable table({"outcome", "count", "share"}, "lrr");
  for (const harness::OutcomeRow& row : harness::TabulateOutcomes(records)) {
    table.AddRow({row.outcome, std::to_string(row.count), fmt::format("{:.1f}%", 100 * row.share)});
  }
  table.AddRow({"total", std::to_string(records.size()), records.empty() ? "" : "100.0%"});
  return table.Format(0);
}

}  // namespace prs::cli
