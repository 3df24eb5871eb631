// More scenes like the failures (docs/search.md, "More scenes like the failures"): the scene
// coordinates of failing episodes, read back from records, fitted by a proposal over the unit
// cube; scenes drawn at its points still go through the exact sampler, so each satisfies the
// whole program. Also the program fingerprint that ties records to the program they came from.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/random.h"
#include "lang/lang.h"
#include "sampling/sampler.h"

namespace prs::search {

/// A fingerprint of the program's meaning for scene coordinates: FNV-1a over every source
/// file's text (in load order) and the -p overrides. Hex, 16 digits.
std::string CalcSpecHash(const lang::CompiledProgram& program);

/// FNV-1a (64 bits) of `bytes`, continuing from `hash`: the fingerprints of programs and the
/// checksums of campaign shards.
inline constexpr uint64_t kFnv1aOffset = 0xCBF29CE484222325ULL;
uint64_t CalcFnv1a(std::string_view bytes, uint64_t hash = kFnv1aOffset);

/// The stream proposal attempt `attempt` of scene `index` draws from: one of its own, apart
/// from every scene's stream (seed, index).
geometry::Rng MakeProposalRng(uint64_t seed, uint64_t index, int64_t attempt);
/// Proposed points a scene may reject before its attempts read the stream alone (so a
/// proposal stuck where every attempt is rejected still finishes its scenes, exactly).
inline constexpr int64_t kMaxProposalAttempts = 100;
/// The narrowest a proposal gets, in coordinate units.
inline constexpr double kMinProposalStd = 0.02;

/// Independent truncated normals per coordinate on [0, 1), mixed with a share of uniform
/// points; attempts after the 100th read the stream (so a scene always finishes, exactly).
/// The cross-entropy method's proposal, and --like's.
class GaussianPoints : public sampling::AttemptPoints {
 public:
  GaussianPoints(std::vector<double> mean, std::vector<double> std, double uniform_share);
  int dimension() const override { return static_cast<int>(mean_.size()); }
  bool Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const override;

 private:
  std::vector<double> mean_, std_;
  double uniform_share_;
};

/// The coordinates of the failing records of a results file, checked against the program.
struct FailureSet {
  std::vector<std::vector<double>> coordinates;  // one per selected record
  int64_t records = 0;                           // lines read
};

/// Reads records (JSON Lines from `prs search -o` or `prs test --design -o`) and keeps the
/// coordinates of those whose outcome is `outcome`, or any failure when `outcome` is empty.
/// Throws std::runtime_error with a message a user can act on: a line that is not a record,
/// records without coordinates or spec hash, records of another program (hash or number of
/// coordinates), or no record with that outcome (naming the outcomes found). `path` names
/// the file in messages.
FailureSet ReadFailures(const std::vector<std::string>& lines, const std::string& path,
                        const std::string& outcome, const std::string& spec_hash, int dimension);

/// The proposal of --like: per coordinate, the failures' mean and standard deviation (at
/// least 0.02), with 5 % uniform points.
GaussianPoints FitLike(const FailureSet& failures);

/// The coordinates of one record of a results file for --near: the record on line `line`
/// (1-based), or with line 0 the first failing one. Throws std::runtime_error as ReadFailures
/// (also for a line past the end, a blank line, or no failing record).
std::vector<double> ReadRecordCoordinates(const std::vector<std::string>& lines,
                                          const std::string& path, int64_t line,
                                          const std::string& spec_hash, int dimension);

}  // namespace prs::search
