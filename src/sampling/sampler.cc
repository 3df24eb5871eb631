// Whole-scene rejection sampling over the interpreter, with per-reason accounting and a
// located failure message when the attempt limit is reached.
#include "sampling/sampler.h"

#include <set>
#include <stdexcept>

#include "sampling/gibbs.h"
#include "sampling/partial_rejection.h"

namespace prs::sampling {

void RejectionCounts::Add(const lang::Rejection& rejection) {
  const auto key = std::make_pair(rejection.kind, rejection.culprit);
  ++by_culprit[key];
  ++by_kind[rejection.kind];
  ++total;
  examples.emplace(key, rejection);
}

void RejectionCounts::Merge(const RejectionCounts& other) {
  for (const auto& [key, n] : other.by_culprit) by_culprit[key] += n;
  for (const auto& [kind, n] : other.by_kind) by_kind[kind] += n;
  total += other.total;
  for (const auto& [key, example] : other.examples) examples.emplace(key, example);
}

// When some attempts made a scene and the scene test (SampleOptions::accept) rejected every
// one, that is the message: the program's own most frequent reason is not what stands in the
// way.
void ThrowSamplingFailure(const RejectionCounts& counts, int64_t attempts, int64_t tested,
                          lang::RejectionKind tested_kind) {
  const std::pair<const std::pair<lang::RejectionKind, std::string>, int64_t>* worst = nullptr;
  for (const auto& entry : counts.by_culprit) {
    if (tested > 0 && entry.first.first != tested_kind) continue;  // the test's culprits only
    if (!worst || entry.second > worst->second) worst = &entry;
  }
  const lang::Rejection& example = counts.examples.at(worst->first);
  lang::Diagnostic d;
  d.id = "sampling-failed";
  d.span = example.span;
  const std::string reason = std::string(lang::RejectionKindName(worst->first.first)) + ": " +
                             worst->first.second + " (" + std::to_string(worst->second) + " times)";
  d.message = tested > 0 ? "no valid scene after " + std::to_string(attempts) + " attempts: the " +
                               std::to_string(tested) +
                               " scenes that met the program's constraints all failed the scene "
                               "test, most often " +
                               reason
                         : "no valid scene after " + std::to_string(attempts) +
                               " attempts; the most frequent reason was " + reason;
  if (!example.detail.empty()) {
    d.notes.push_back({{}, false, "in one such attempt: " + example.detail});
  }
  for (const auto& [kind, n] : counts.by_kind) {
    d.notes.push_back(
        {{},
         false,
         std::string(lang::RejectionKindName(kind)) + ": " + std::to_string(n) + " rejections"});
  }
  d.notes.push_back({{}, false, "relax this constraint, or raise the limit with --max-attempts"});
  throw lang::ScenarioError(std::move(d));
}

namespace {

// Throws "sampling-failed" for a rejection that every attempt would repeat.
[[noreturn]] void ThrowCertainFailure(const lang::Rejection& rejection) {
  lang::Diagnostic d;
  d.id = "sampling-failed";
  d.span = rejection.span;
  d.message = std::string(
                  "every attempt fails the same way (nothing random is drawn before "
                  "it): ") +
              lang::RejectionKindName(rejection.kind) + ": " + rejection.culprit;
  if (!rejection.detail.empty()) d.notes.push_back({{}, false, rejection.detail});
  d.notes.push_back({{}, false, "change the fixed values so that this constraint can hold"});
  throw lang::ScenarioError(std::move(d));
}

// Whether two streams are at the same place: their next draws agree (two different states give
// the same 64 bits with probability 2^-64).
bool IsSameStream(geometry::Rng a, geometry::Rng b) { return a.NextU64() == b.NextU64(); }

}  // namespace

SceneSampler::SceneSampler(const lang::CompiledProgram& program, SampleOptions options)
    : program_(program), options_(std::move(options)), cache_(lang::MakeRunCache()) {
  if (options_.gibbs && options_.points) {
    lang::Diagnostic d;
    d.id = "gibbs-unsupported";
    d.has_span = false;  // the command line's doing, not the program's
    d.message =
        "--sampler gibbs chooses its own scene coordinates, so it cannot draw scenes at given "
        "points (--design, --like, --near, prs search, prs estimate, --replay)";
    d.notes.push_back({{}, false, "leave --sampler gibbs out of this command"});
    throw lang::ScenarioError(std::move(d));
  }
  if (options_.partial_rejection && (options_.points || options_.gibbs)) {
    lang::Diagnostic d;
    d.id = "partial-rejection-unsupported";
    d.has_span = false;
    d.message = options_.gibbs ? "--sampler takes one method, not both gibbs and "
                                 "partial-rejection"
                               : "--sampler partial-rejection chooses its own scene coordinates, "
                                 "so it cannot draw scenes at given points (--design, --like, "
                                 "--near, prs search, prs estimate, --replay)";
    d.notes.push_back({{}, false, "leave --sampler partial-rejection out of this command"});
    throw lang::ScenarioError(std::move(d));
  }
  if (options_.gibbs) gibbs_ = std::make_unique<GibbsChain>(program_, options_);
  if (options_.partial_rejection) {
    partial_ = std::make_unique<PartialRejectionSampler>(program_, options_);
  }
}

SceneSampler::~SceneSampler() = default;

SampledScene SceneSampler::Sample(uint64_t seed, uint64_t index) {
  if (gibbs_) return gibbs_->Sample(seed, index);
  if (partial_) return partial_->Sample(seed, index);
  SampledScene result;
  result.seed = seed;
  result.index = index;
  geometry::Rng rng(seed, index);
  lang::RunOptions run = options_.run;
  run.cache = options_.use_run_cache ? cache_.get() : nullptr;
  const AttemptPoints* points = options_.points;
  std::vector<double> u(points ? points->dimension() : 0);
  std::set<std::pair<lang::RejectionKind, std::string>> explained;
  run.explained = &explained;
  int64_t tested = 0;  // scenes the program made, all rejected by options_.accept so far
  lang::RejectionKind tested_kind = lang::RejectionKind::kUnstable;
  while (result.attempts < options_.max_attempts) {
    const bool at_point = points && points->Point(seed, index, result.attempts, u.data());
    run.coordinates = at_point ? lang::CoordinateInput{u.data(), static_cast<int>(u.size())}
                               : lang::CoordinateInput{};
    ++result.attempts;
    if (options_.live) options_.live->attempts.fetch_add(1, std::memory_order_relaxed);
    const geometry::Rng rng_before = rng;
    lang::AttemptResult attempt = lang::RunAttempt(program_, rng, run);
    if (auto* scene = std::get_if<lang::Scene>(&attempt)) {
      std::optional<lang::Rejection> failed =
          options_.accept ? options_.accept(*scene) : std::nullopt;
      if (!failed) {
        result.scene = std::move(*scene);
        if (at_point) result.coordinates = std::move(u);
        return result;
      }
      // Without a draw (the stream did not move, and no point was given), every attempt
      // would make this scene again.
      failed->certain = !at_point && IsSameStream(rng_before, rng);
      ++tested;
      tested_kind = failed->kind;
      attempt = std::move(*failed);
    }
    if (options_.live) options_.live->rejections.fetch_add(1, std::memory_order_relaxed);
    const lang::Rejection& rejection = std::get<lang::Rejection>(attempt);
    result.rejections.Add(rejection);
    explained.emplace(rejection.kind, rejection.culprit);
    // Nothing random ran, so retrying would only repeat this rejection.
    if (rejection.certain) ThrowCertainFailure(rejection);
  }
  ThrowSamplingFailure(result.rejections, result.attempts, tested, tested_kind);
}

std::vector<lang::CoordinateInfo> DescribeCoordinates(const lang::CompiledProgram& program,
                                                      const SampleOptions& options,
                                                      int probe_attempts) {
  std::vector<lang::CoordinateInfo> longest;
  geometry::Rng rng(0, 0);
  lang::RunOptions run = options.run;
  run.cache = nullptr;
  for (int i = 0; i < probe_attempts; ++i) {
    std::vector<lang::CoordinateInfo> log;
    run.coordinates = {nullptr, 0, &log};
    const lang::AttemptResult attempt = lang::RunAttempt(program, rng, run);
    if (log.size() > longest.size()) longest = std::move(log);
    const auto* rejection = std::get_if<lang::Rejection>(&attempt);
    if (rejection && rejection->certain) break;  // every attempt is the same
  }
  if (longest.size() > static_cast<size_t>(kMaxCoordinates)) longest.resize(kMaxCoordinates);
  // Several draws named after one property (V3D((0, 1), (0, 1), 0) as a position) are told
  // apart by where they are in the source.
  std::map<std::string, int> uses;
  for (const lang::CoordinateInfo& c : longest) ++uses[c.name];
  for (lang::CoordinateInfo& c : longest) {
    if (uses[c.name] < 2) continue;
    const lang::LineColumn where = program.sources.CalcLineColumn(c.span.file, c.span.begin);
    c.name += " (" + std::to_string(where.line) + ":" + std::to_string(where.column) + ")";
  }
  return longest;
}

SampledScene SampleScene(const lang::CompiledProgram& program, uint64_t seed, uint64_t index,
                         const SampleOptions& options) {
  return SceneSampler(program, options).Sample(seed, index);
}

}  // namespace prs::sampling
