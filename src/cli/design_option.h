// `--design random|sobol|halton|lattice` of `prs sample` and `prs test`: the first attempt of
// scene i runs at point i of a space-filling design over the scene coordinates (docs/search.md).
#pragma once

#include <memory>
#include <string>

#include "cli/common.h"
#include "search/design.h"

namespace prs::cli {

struct DesignArgs {
  std::string name = "random";
};

/// Adds --design (checked, with a did-you-mean) to `command`.
void AddDesignOption(CLI::App& command, DesignArgs& args);

/// Builds the design for `program` and points `sample` at it (a lattice is built for the
/// scenes 0..start+count-1). Nothing to do for "random", or for a program that draws nothing
/// at random (then a note says so). Returns false after printing a usage error (a lattice too
/// large, or --sampler gibbs or partial-rejection, which choose their own points); throws
/// lang::ScenarioError when the program fails while its coordinates are probed.
bool PrepareDesign(const DesignArgs& args, const lang::CompiledProgram& program,
                   const SceneRangeArgs& range, sampling::SampleOptions& sample,
                   std::unique_ptr<search::Design>* design);

}  // namespace prs::cli
