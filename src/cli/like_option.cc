// --like and --near (like_option.h): the proposal fitted to a records file's failures, or
// normals around one of its episodes.
#include "cli/like_option.h"

#include <fmt/format.h>

#include <charconv>

#include "cli/common.h"
#include "search/search.h"

namespace prs::cli {

void AddLikeOptions(CLI::App& command, LikeArgs& args) {
  CLI::Option* like =
      command
          .add_option("--like", args.like,
                      "draw scenes like the failing episodes of RESULTS (prs search -o, or prs "
                      "test --design -o): each still satisfies the whole program")
          ->type_name("RESULTS")
          ->check(NonEmptyPath())
          ->excludes(command.get_option("--design"));
  command.add_option("--outcome", args.outcome, "with --like: only episodes with this outcome")
      ->type_name("NAME")
      ->needs(like);
  CLI::Option* near =
      command
          .add_option("--near", args.near,
                      "draw scenes near one episode of RESULTS (LINE, or its first failure): "
                      "small changes that keep the whole program satisfied")
          ->type_name("RESULTS[:LINE]")
          ->check(NonEmptyPath())
          ->excludes(command.get_option("--design"))
          ->excludes(like);
  command
      .add_option("--scale", args.scale,
                  "with --near: the standard deviation of the changes, in scene coordinates")
      ->type_name("S")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str()
      ->needs(near);
}

// --like: the proposal fitted to the failures of the records file; --near: normals of
// standard deviation --scale around one record's coordinates.
bool PrepareLike(const LikeArgs& args, const lang::CompiledProgram& program,
                 sampling::SampleOptions& sample, std::unique_ptr<search::GaussianPoints>& proposal,
                 bool quiet) {
  if (!CheckSamplerTakesPoints(sample, args.near.empty() ? "--like" : "--near",
                               "leave out --sampler (the default, rejection, is exact for any "
                               "program)")) {
    return false;
  }
  std::string path = args.near.empty() ? args.like : args.near;
  int64_t line = 0;
  const size_t colon = path.rfind(':');
  if (!args.near.empty() && colon != std::string::npos && colon + 1 < path.size() &&
      path.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
    const char* digits = path.c_str() + colon + 1;
    if (std::from_chars(digits, path.c_str() + path.size(), line).ec != std::errc()) {
      PrintError("--near: no such line " + path.substr(colon + 1) + " in " + path.substr(0, colon));
      return false;
    }
    path.resize(colon);
  }
  const auto lines = ReadLines(path);
  if (!lines) return false;
  const int dimension = static_cast<int>(sampling::DescribeCoordinates(program, sample).size());
  try {
    if (dimension == 0) {
      throw std::runtime_error(std::string(args.near.empty() ? "--like" : "--near") +
                               ": this program draws nothing at random, so every scene is "
                               "like every other");
    }
    if (!args.near.empty()) {
      const std::vector<double> centre = search::ReadRecordCoordinates(
          *lines, path, line, search::CalcSpecHash(program), dimension);
      proposal = std::make_unique<search::GaussianPoints>(
          centre, std::vector<double>(centre.size(), args.scale), 0.0);
      sample.points = proposal.get();
      if (!quiet) {
        PrintNote(fmt::format("drawing scenes near {} {} (scale {})", path,
                              line ? fmt::format("line {}", line) : "(its first failure)",
                              args.scale));
      }
      return true;
    }
    const search::FailureSet failures = search::ReadFailures(
        *lines, args.like, args.outcome, search::CalcSpecHash(program), dimension);
    proposal = std::make_unique<search::GaussianPoints>(search::FitLike(failures));
    if (!quiet) {
      PrintNote(fmt::format("drawing scenes like the {} of {}",
                            FormatCount(static_cast<int64_t>(failures.coordinates.size()),
                                        args.outcome.empty() ? "failure" : args.outcome),
                            args.like));
    }
  } catch (const std::runtime_error& error) {
    PrintError(error.what());
    return false;
  }
  sample.points = proposal.get();
  return true;
}

}  // namespace prs::cli
