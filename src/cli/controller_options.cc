// Controller choice and the outcome table, shared by `prs test` and `prs search`.
#include "cli/controller_options.h"

#include <fmt/format.h>

#include <filesystem>

#include "controllers/builtin.h"
#include "cli/text_table.h"
#include "harness/registry.h"

namespace prs::cli {
namespace {

CLI::Validator PositiveSeconds() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        size_t used = 0;
        double value = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == text.size() && value > 0 && value < 1e6) return "";
        return "expects a number of seconds above 0 (and below 10^6), got '" + text + "'";
      },
      "");
}

}  // namespace

void AddControllerOptions(CLI::App& command, ControllerArgs& args) {
  controllers::RegisterBuiltInControllers();
  CLI::Option* controller = command
                                .add_option("--controller", args.controller,
                                            "a built-in controller (" + ListControllerNames() + ")")
                                ->type_name("NAME");
  command
      .add_option("--exec", args.exec,
                  "your own controller: a shell command run once per scene (docs/harness.md)")
      ->type_name("CMD")
      ->excludes(controller);
  command.add_option("--timeout", args.timeout_s, "seconds an --exec episode may take")
      ->type_name("S")
      ->check(PositiveSeconds())
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
  if (auto factory =
          controllers::MakeControllerFactory(args.controller, args.exec, args.timeout_s, &cancel)) {
    return factory;
  }
  std::vector<std::string> names;
  for (const harness::ControllerInfo& info : harness::ListControllers()) names.push_back(info.name);
  const std::string suggestion = lang::SuggestClosest(args.controller, names);
  PrintError("--controller: unknown controller '" + args.controller + "'" +
             (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?") +
             " (controllers: " + ListControllerNames() + ")");
  return std::nullopt;
}

std::vector<std::string> MakeScenarioWords(const ScenarioArgs& scenario,
                                           const SamplingArgs& sampling) {
  std::vector<std::string> words = {scenario.file};
  for (const std::string& dir : scenario.include_dirs) words.insert(words.end(), {"-I", dir});
  for (const std::string& param : scenario.params) words.insert(words.end(), {"-p", param});
  if (sampling.naive) words.push_back("--naive");
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
