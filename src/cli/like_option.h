// `--like RESULTS [--outcome NAME]` and `--near RESULTS[:LINE] [--scale S]` of `prs sample` and
// `prs dataset`: scenes drawn like the failures of a records file, or near one episode, each
// still satisfying the whole program (docs/search.md, "Scenes like the failures").
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "lang/lang.h"
#include "sampling/sampler.h"
#include "search/like.h"

namespace prs::cli {

struct LikeArgs {
  std::string like;     // --like RESULTS.jsonl
  std::string outcome;  // --outcome NAME (with --like)
  std::string near;     // --near RESULTS.jsonl[:LINE]
  double scale = 0.05;  // --scale S (with --near)

  bool given() const { return !like.empty() || !near.empty(); }
};

/// Adds --like, --outcome, --near and --scale to `command`, which must already have --design
/// (they exclude it).
void AddLikeOptions(CLI::App& command, LikeArgs& args);

/// Points `sample` at the proposal --like or --near asks for (`proposal` owns it; it must
/// outlive the sampling). Returns false after printing the error (a sampler that chooses its
/// own points, an unreadable or foreign records file, a program that draws nothing at random);
/// prints what it draws from unless `quiet`.
bool PrepareLike(const LikeArgs& args, const lang::CompiledProgram& program,
                 sampling::SampleOptions& sample, std::unique_ptr<search::GaussianPoints>& proposal,
                 bool quiet);

}  // namespace prs::cli
