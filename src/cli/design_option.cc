// --design: choosing a space-filling design and wiring it into the sampler.
#include "cli/design_option.h"

#include "lang/diagnostics.h"

namespace prs::cli {

void AddDesignOption(CLI::App& command, DesignArgs& args) {
  command
      .add_option("--design", args.name,
                  "where each scene's first attempt runs: random (i.i.d., the default), or a "
                  "scrambled sobol, halton or lattice design over the scene coordinates")
      ->type_name("D")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            search::DesignKind kind;
            if (search::ParseDesign(text, &kind)) return "";
            const std::string suggestion = lang::SuggestClosest(text, search::DesignNames());
            return "unknown design '" + text + "'" +
                   (suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?") +
                   " (designs: random, sobol, halton, lattice)";
          },
          ""))
      ->capture_default_str();
}

bool PrepareDesign(const DesignArgs& args, const lang::CompiledProgram& program,
                   const SceneRangeArgs& range, sampling::SampleOptions& sample,
                   std::unique_ptr<search::Design>* design) {
  search::DesignKind kind = search::DesignKind::kRandom;
  search::ParseDesign(args.name, &kind);
  if (kind == search::DesignKind::kRandom) return true;
  if (!CheckSamplerTakesPoints(sample, "--design " + args.name,
                               "leave out --design (scenes then come from the sampler alone), "
                               "or --sampler (the default, rejection, is exact for any program "
                               "and runs each scene's first attempt at the design's point)")) {
    return false;
  }
  const int dimension = static_cast<int>(sampling::DescribeCoordinates(program, sample).size());
  if (dimension == 0) {
    PrintNote("--design " + args.name +
              " has no effect: this program draws nothing at random (prs check --coordinates)");
    return true;
  }
  const uint64_t size = range.start + static_cast<uint64_t>(range.count);
  if (kind == search::DesignKind::kLattice && (size < 1 || size > (uint64_t{1} << 32))) {
    PrintError(
        "--design lattice: the lattice is built for scenes 0..start+count-1, which must "
        "be 1 to 2^32 scenes");
    return false;
  }
  *design = std::make_unique<search::Design>(kind, dimension, size);
  sample.points = design->get();
  return true;
}

}  // namespace prs::cli
