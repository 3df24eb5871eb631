// Shared pieces of the `prs` commands: options, compiling the scenario, reporting errors.
#include "cli/common.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>
#include <thread>

#include "sampling/gibbs.h"
#include "sampling/partial_rejection.h"

namespace prs::cli {
namespace {

// -p NAME=VALUE: a non-empty NAME before the first '='.
CLI::Validator ParamAssignment() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const size_t eq = text.find('=');
        if (eq == std::string::npos || eq == 0) return "expects NAME=VALUE, got '" + text + "'";
        return "";
      },
      "");
}

std::vector<std::pair<std::string, std::string>> SplitParams(
    const std::vector<std::string>& params) {
  std::vector<std::pair<std::string, std::string>> overrides;
  for (const std::string& p : params) {
    const size_t eq = p.find('=');  // the validator guaranteed one
    overrides.emplace_back(p.substr(0, eq), p.substr(eq + 1));
  }
  return overrides;
}

std::vector<std::string> SplitPrsPath() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("PRS_PATH")) {
    std::stringstream path(env);
    for (std::string dir; std::getline(path, dir, ':');) {
      if (!dir.empty()) dirs.push_back(dir);
    }
  }
  return dirs;
}

bool UseColor() { return IsStderrTerminal() && std::getenv("NO_COLOR") == nullptr; }

// Whether `command` or one of its subcommands (`campaign init`) has the option `name`.
bool HasOption(const CLI::App& command, const std::string& name) {
  if (command.get_option_no_throw(name)) return true;
  for (const CLI::App* sub : command.get_subcommands([](const CLI::App*) { return true; })) {
    if (HasOption(*sub, name)) return true;
  }
  return false;
}

// --stable=T, --settle=T: a T the physics check takes (`check` throws std::invalid_argument
// with its message otherwise: below the least time in which rest can be decided). After
// PositiveNumber, so the text is a number.
CLI::Validator PhysicsCheckTakes(std::function<void(double)> check) {
  return CLI::Validator(
      [check](std::string& text) -> std::string {
        try {
          check(std::stod(text));
        } catch (const std::exception& error) {
          return error.what();
        }
        return "";
      },
      "");
}

// `require settled` is checked only on settled scenes: without --settle, the first scene that
// ran one says so, once a run of prs, at the statement.
sampling::SceneTest WarnOfUnsettledRequirements(sampling::SceneTest test) {
  return [test = std::move(test)](lang::Scene& scene) -> std::optional<lang::Rejection> {
    static std::once_flag warned;
    if (!scene.settled_requirements.empty()) {
      std::call_once(warned, [&] {
        const lang::SettledRequirement& r = scene.settled_requirements.front();
        const lang::LineColumn where = r.program->sources.CalcLineColumn(r.span.file, r.span.begin);
        PrintWarning(fmt::format(
            "{}:{}:{}: `require settled` is checked only on settled scenes, so without --settle "
            "it is ignored (give --settle[=T] to let the scene come to rest first)",
            r.program->sources.path(r.span.file), where.line, where.column));
      });
    }
    return test ? test(scene) : std::nullopt;
  };
}

}  // namespace

CLI::Validator IntegerInRange(int64_t min, int64_t max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error == std::errc() && stop == end && value >= min && value <= max) return "";
        if (max == std::numeric_limits<int64_t>::max()) {
          return "expects an integer >= " + std::to_string(min) + ", got '" + text + "'";
        }
        return "expects an integer from " + std::to_string(min) + " to " + std::to_string(max) +
               ", got '" + text + "'";
      },
      "");
}

CLI::Validator IntegerAtLeast(int64_t min) {
  return IntegerInRange(min, std::numeric_limits<int64_t>::max());
}

CLI::Validator NonEmptyPath() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "expects a path, got an empty one (for stdout, leave the option out "
                              "or give -)"
                            : "";
      },
      "");
}

CLI::Validator PositiveNumber(const std::string& of_what) {
  return CLI::Validator(
      [of_what](std::string& text) -> std::string {
        size_t used = 0;
        double value = 0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == text.size() && value > 0 && value < 1e6) return "";
        return "expects a number of " + of_what + " above 0 (and below 10^6), got '" + text + "'";
      },
      "");
}

// Digits only, so that "-1" is not wrapped around to 2^64 - 1, and within 64 bits.
CLI::Validator UnsignedIntegerText() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (digits && error == std::errc() && stop == end) return "";
        return "expects an integer from 0 to 2^64 - 1, got '" + text + "'";
      },
      "");
}

void AddScenarioOptions(CLI::App& command, ScenarioArgs& args) {
  command.add_option("FILE", args.file, "the .prs scenario")->required();
  command.add_option("-I", args.include_dirs, "a directory searched for imported modules")
      ->type_name("DIR")
      ->allow_extra_args(false);
  command.add_option("-p,--param", args.params, "override a param")
      ->type_name("NAME=VALUE")
      ->check(ParamAssignment())
      ->allow_extra_args(false);
}

void AddSceneRangeOptions(CLI::App& command, SceneRangeArgs& args, int64_t min_count) {
  command.add_option("-n,--count", args.count, "number of scenes")
      ->type_name("N")
      ->check(IntegerAtLeast(min_count))
      ->capture_default_str();
  command.add_option("--start", args.start, "index of the first scene")
      ->type_name("I")
      ->check(UnsignedIntegerText())
      ->capture_default_str();
}

bool CheckSceneRange(const SceneRangeArgs& args) {
  if (args.count == 0 ||
      args.start <= std::numeric_limits<uint64_t>::max() - uint64_t(args.count - 1)) {
    return true;
  }
  PrintError("--start " + std::to_string(args.start) + " with -n " + std::to_string(args.count) +
             " runs past the last scene index, 2^64 - 1");
  return false;
}

void AddSamplingOptions(CLI::App& command, SamplingArgs& args) {
  args.threads = CountHardwareThreads();
  command.add_option("-s,--seed", args.seed, "random seed")
      ->type_name("S")
      ->check(UnsignedIntegerText())
      ->capture_default_str();
  command.add_option("--threads", args.threads, "worker threads (default: all hardware threads)")
      ->type_name("T")
      ->check(IntegerInRange(1, 1024))
      ->capture_default_str();
  command.add_flag("--naive", args.naive,
                   "the paper's baseline: positions from the workspace, specifiers checked after");
  command
      .add_option("--sampler", args.sampler,
                  "rejection (exact, the default), partial-rejection (exact, for clutter: "
                  "objects that only must not overlap) or gibbs (a Markov chain over the scene "
                  "coordinates, for clutter too dense for both; correlated scenes): "
                  "docs/sampling.md")
      ->type_name("KIND")
      ->check(CLI::IsMember({"rejection", "partial-rejection", "gibbs"}))
      ->capture_default_str();
  command.add_option("--max-attempts", args.max_attempts, "attempts per scene before failing")
      ->type_name("K")
      ->check(IntegerAtLeast(1))
      ->capture_default_str();
  command
      .add_flag("--stable{1}", args.stable_s,
                "keep only scenes whose free bodies stay put under gravity for T simulated "
                "seconds (--stable=T; default 1, at least 0.2; docs/physics.md)")
      ->check(PositiveNumber("seconds"))
      ->check(PhysicsCheckTakes([](double t) { sim::CheckStabilityOptions({t}); }));
  command.add_option("--stable-move", args.stable_move_m, "--stable: metres a body may move")
      ->type_name("M")
      ->check(PositiveNumber("metres"))
      ->capture_default_str();
  command.add_option("--stable-turn", args.stable_turn_deg, "--stable: degrees a body may turn")
      ->type_name("DEG")
      ->check(PositiveNumber("degrees"))
      ->capture_default_str();
  command
      .add_flag("--settle{4}", args.settle_s,
                "let the free bodies fall and come to rest (found at rest within T simulated "
                "seconds, then confirmed for 1 s: --settle=T; default 4, at least 0.5), then "
                "check the workspace and `require settled` (docs/physics.md)")
      ->check(PositiveNumber("seconds"))
      ->check(PhysicsCheckTakes([](double t) { sim::CheckSettleOptions({t}); }))
      ->excludes("--stable");
}

std::optional<std::string> DiagnoseSpacedFlagValue(const CLI::App& command,
                                                   const std::vector<std::string>& args) {
  for (size_t i = 0; i + 1 < args.size() && args[i] != "--"; ++i) {
    const std::string& flag = args[i];
    if ((flag != "--stable" && flag != "--settle") || !HasOption(command, flag)) continue;
    const std::string& value = args[i + 1];
    size_t used = 0;
    try {
      std::stod(value, &used);
    } catch (const std::exception&) {
      continue;
    }
    if (used != value.size()) continue;
    return fmt::format(
        "{} takes its time after '=': write {}={} ({} alone means {} s, and a word after it is "
        "not its value)",
        flag, flag, value, flag, flag == "--stable" ? 1 : 3);
  }
  return std::nullopt;
}

sim::PhysicsCheck MakePhysicsCheck(const SamplingArgs& args) {
  // The numbers were checked by PositiveNumber; --stable and --settle exclude each other.
  sim::PhysicsCheck check;
  if (!args.stable_s.empty()) check.stable_s = std::stod(args.stable_s);
  check.stable_move_m = args.stable_move_m;
  check.stable_turn_deg = args.stable_turn_deg;
  if (!args.settle_s.empty()) check.settle_s = std::stod(args.settle_s);
  return check;
}

int CountHardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

std::unique_ptr<lang::CompiledProgram> CompileScenario(const ScenarioArgs& args) {
  lang::CompileOptions options;
  options.search_path = args.include_dirs;
  for (std::string& dir : SplitPrsPath()) options.search_path.push_back(std::move(dir));
  options.param_overrides = SplitParams(args.params);
  options.on_note = [](const std::string& note) { PrintNote(note); };
  lang::DiagnosticEngine diagnostics;
  auto program = lang::CompileFile(args.file, options, diagnostics);
  const bool color = UseColor();
  for (const lang::Diagnostic& d : diagnostics.diagnostics()) {
    std::cerr << lang::RenderDiagnostic(d, program->sources, color);
  }
  if (diagnostics.has_errors()) return nullptr;
  return program;
}

sampling::SampleOptions MakeSampleOptions(const SamplingArgs& args) {
  sampling::SampleOptions options;
  options.max_attempts = args.max_attempts;
  options.run.mode = args.naive ? lang::SamplingMode::kNaive : lang::SamplingMode::kRegion;
  options.accept = sim::MakePhysicsTest(MakePhysicsCheck(args));
  if (args.settle_s.empty()) options.accept = WarnOfUnsettledRequirements(options.accept);
  if (args.sampler == "gibbs") options.gibbs = std::make_shared<sampling::GibbsRequest>();
  if (args.sampler == "partial-rejection") {
    options.partial_rejection = std::make_shared<sampling::PartialRejectionRequest>();
  }
  return options;
}

std::string DescribeGibbs(const sampling::SampleOptions& options, int64_t scenes) {
  if (!options.gibbs) return "";
  const std::optional<sampling::GibbsPlan> plan = options.gibbs->plan();
  if (!plan) return "";
  return fmt::format(
      "--sampler gibbs: these scenes come from Markov chains ({} scenes a chain) and are "
      "correlated, not independent: autocorrelation time {:.1f} sweeps (the slowest statistic, "
      "{}: {:.1f}), {} between scenes, {} of burn-in; {} {} worth about {:.0f} independent ones",
      plan->scenes_per_chain, plan->tau_sweeps, plan->tau_statistic, plan->tau_worst_sweeps,
      FormatCount(plan->thin_sweeps, "sweep"), FormatCount(plan->burn_in_sweeps, "sweep"),
      FormatCount(scenes, "scene"), scenes == 1 ? "is" : "are", plan->CalcEffectiveScenes(scenes));
}

std::string FormatSamplingCounts(const sampling::BatchSummary& summary,
                                 const sampling::SampleOptions& options) {
  std::string reasons;
  for (const auto& [kind, n] : summary.rejections.by_kind) {
    reasons +=
        fmt::format("{}{} {}", reasons.empty() ? "" : ", ", lang::RejectionKindName(kind), n);
  }
  if (!reasons.empty()) reasons = " (" + reasons + ")";
  const std::string scenes = FormatCount(summary.scenes, "scene");
  const int64_t rejected = summary.rejections.total;
  if (options.gibbs) {
    // A scene is a stretch of a chain: every run is one try of a move, accepted or not.
    return fmt::format("{}, {} (Gibbs moves, each redrawing one object), {} rejected{}", scenes,
                       FormatCount(summary.attempts, "program run"), rejected, reasons);
  }
  if (options.partial_rejection) {
    // Probe runs of one object each make the hard-core draws; only the whole-scene runs that
    // follow are rejected (by the requirements), and counted.
    return fmt::format(
        "{}, {} (one-object probes of hard-core draws, and whole scenes), {} rejected{}", scenes,
        FormatCount(summary.attempts, "program run"), FormatCount(rejected, "whole scene"),
        reasons);
  }
  return fmt::format("{}, {}, {}{}", scenes, FormatCount(summary.attempts, "attempt"),
                     FormatCount(rejected, "rejection"), reasons);
}

bool CheckSamplerTakesPoints(const sampling::SampleOptions& options, std::string_view with,
                             std::string_view instead) {
  if (!options.gibbs && !options.partial_rejection) return true;
  PrintError(fmt::format(
      "--sampler {} cannot be used with {}: {} chooses the scene coordinates of each scene "
      "itself, and the {} chooses its own; {}",
      options.gibbs ? "gibbs" : "partial-rejection", with, with,
      options.gibbs ? "Gibbs chain" : "partial rejection sampler", instead));
  return false;
}

bool CheckSamplerTakesPoints(const SamplingArgs& args, std::string_view with,
                             std::string_view instead) {
  return CheckSamplerTakesPoints(MakeSampleOptions(args), with, instead);
}

sampling::BatchOptions MakeBatchOptions(const SamplingArgs& args, int64_t count,
                                        const std::atomic<bool>& cancel) {
  sampling::BatchOptions options;
  options.sample = MakeSampleOptions(args);
  options.seed = args.seed;
  options.count = count;
  options.threads = args.threads;
  options.cancel = &cancel;
  return options;
}

int ReportScenarioError(const lang::ScenarioError& error, const lang::SourceManager& sources) {
  std::cerr << lang::RenderDiagnostic(error.diagnostic(), sources, UseColor());
  const std::string& id = error.diagnostic().id;
  return id == "sampling-failed" || id == "partial-rejection-too-dense" ? kExitSamplingFailure
                                                                        : kExitScenarioError;
}

std::string FormatCount(int64_t n, std::string_view noun) {
  std::string text = std::to_string(n) + " " + std::string(noun);
  if (n != 1) text += noun.ends_with("s") ? "es" : "s";
  return text;
}

void PrintError(std::string_view message) { std::cerr << "prs: error: " << message << '\n'; }

void PrintNote(std::string_view message) { std::cerr << "prs: " << message << '\n'; }

void PrintWarning(std::string_view message) { std::cerr << "prs: warning: " << message << '\n'; }

void WarnOnce::operator()(const std::string& warning) {
  if (!printed_->insert(warning).second) return;
  if (before_) before_();
  PrintWarning(warning);
}

bool IsStderrTerminal() { return ::isatty(STDERR_FILENO) == 1; }

bool IsStdoutTerminal() { return ::isatty(STDOUT_FILENO) == 1; }

bool IsScenesFile(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".jsonl" || extension == ".json" || extension == ".ndjson";
}

std::optional<std::vector<std::string>> ReadLines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    PrintError(fmt::format("cannot read {}: {}", path, std::strerror(errno)));
    return std::nullopt;
  }
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

int64_t CountNonBlank(const std::vector<std::string>& lines) {
  int64_t n = 0;
  for (const std::string& line : lines) n += !IsBlankLine(line);
  return n;
}

bool IsBlankLine(std::string_view line) {
  return line.find_first_not_of(" \t\r") == std::string_view::npos;
}

void PrintNoScenes(const std::string& path) {
  PrintError(
      fmt::format("{} has no scenes: it is empty (write one with prs sample -o FILE)", path));
}

}  // namespace prs::cli
