// prs estimate: the adaptation loop (weighted cross-entropy toward failures), the importance-
// sampling run from a defensive mixture, and the self-normalised estimator with its delta-method
// interval (derivations in docs/search.md).
#include "search/estimate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "search/intervals.h"
#include "search/like.h"
#include "search/search.h"

namespace prs::search {
namespace {

// The records by score, lowest (nearest to failing) first; empty when a record has no score.
std::vector<const WeightedOutcome*> SortByScore(const std::vector<WeightedOutcome>& records) {
  std::vector<const WeightedOutcome*> by_score;
  for (const WeightedOutcome& r : records) {
    if (std::isnan(r.score)) return {};
    by_score.push_back(&r);
  }
  std::stable_sort(by_score.begin(), by_score.end(),
                   [](const auto* a, const auto* b) { return a->score < b->score; });
  return by_score;
}

// Estimate::uncovered_share: the draws with the lowest scores, as many as make
// kNearFailureMass of the weight (of the program's law), and the weighted share of them drawn
// where the normals give under half the proposal's density. NaN when a record has no score or
// no kernel share.
double CalcUncoveredShare(const std::vector<WeightedOutcome>& records, double total_weight) {
  for (const WeightedOutcome& r : records) {
    if (std::isnan(r.kernel_share)) return NAN;
  }
  const std::vector<const WeightedOutcome*> by_score = SortByScore(records);
  if (by_score.empty()) return NAN;
  double near = 0, uncovered = 0;
  for (const WeightedOutcome* r : by_score) {
    if (near >= kNearFailureMass * total_weight && r->score > 0) break;
    near += r->weight;
    if (r->kernel_share < 0.5) uncovered += r->weight;
  }
  return near > 0 ? uncovered / near : NAN;
}

// How much larger a failure's variance may be than its failing draws say: the variance rests
// on the mean weight over the failure set, which the failing draws estimate where the proposal
// put them and so under-weigh the set's edges, where the proposal is thin and weights are
// large. The draws nearest to failing (the lowest scores, kEdgeMass times the failures'
// weight, the failures among them) reach those edges more often: the ratio of their mean
// weight (sum w^2 / sum w) to the failures', when above 1. 1 without scores.
double CalcEdgeFactor(const std::vector<WeightedOutcome>& records, const std::string& outcome) {
  double failing = 0, failing_squares = 0;
  for (const WeightedOutcome& r : records) {
    if (r.outcome == outcome) failing += r.weight, failing_squares += r.weight * r.weight;
  }
  const std::vector<const WeightedOutcome*> by_score = SortByScore(records);
  if (by_score.empty() || !(failing > 0)) return 1;
  double near = 0, near_squares = 0;
  for (const WeightedOutcome* r : by_score) {
    if (near >= kEdgeMass * failing) break;
    near += r->weight;
    near_squares += r->weight * r->weight;
  }
  return std::max(1.0, (near_squares / near) / (failing_squares / failing));
}

}  // namespace

std::string DescribeUnreliable(const Estimate& e) {
  if (e.reliable) return "";
  if (e.uncovered_share > kMaxUncoveredShare) {
    return fmt::format(
        "the proposal misses where the controller nearly fails: {:.0f} % of the episodes "
        "nearest to failing ({:.0f} % of the scenes, by score) were drawn where only its uniform "
        "share reaches, so the failure set may extend where it drew too little to tell; no "
        "estimate is given, as its interval could not be trusted (docs/search.md, \"How "
        "good\"); raise --budget",
        100 * e.uncovered_share, 100 * kNearFailureMass);
  }
  return fmt::format(
      "the weights degenerate (effective sample size {:.0f} of {} weighted episodes): no "
      "estimate is given, as its interval could not be trusted; raise --budget",
      e.ess, e.episodes);
}

Estimate CalcEstimate(const std::vector<WeightedOutcome>& records,
                      const std::vector<std::string>& also_seen) {
  if (records.empty()) throw std::invalid_argument("no records to estimate from");
  Estimate estimate;
  estimate.episodes = int64_t(records.size());
  double total = 0, squares = 0, share = 1;
  std::map<std::string, std::pair<double, int64_t>> failed;  // outcome -> (weight, episodes)
  for (const WeightedOutcome& r : records) {
    if (!(r.weight > 0) || !std::isfinite(r.weight)) {
      throw std::invalid_argument(
          fmt::format("a record's weight is {}, not a positive number", r.weight));
    }
    total += r.weight;
    squares += r.weight * r.weight;
    share = std::min(share, r.uniform_share);
    estimate.iid = estimate.iid && r.weight == 1 && r.uniform_share == 1;
    if (r.outcome == "success") continue;
    failed[r.outcome].first += r.weight;
    ++failed[r.outcome].second;
  }
  estimate.ess = total * total / squares;
  estimate.reliable = estimate.ess >= kMinEss && estimate.ess >= 0.05 * double(estimate.episodes);
  estimate.uncovered_share = CalcUncoveredShare(records, total);
  if (estimate.uncovered_share > kMaxUncoveredShare) estimate.reliable = false;
  const bool normalised =
      std::any_of(records.begin(), records.end(), [](const auto& r) { return r.normalised; });
  const double n = double(records.size());
  // No failure of a kind in n draws from the proposal: P(that kind | proposal) <= 1 - 0.05^(1/n)
  // at 95 %, and p = E[w 1F] / E[w] <= P(fail | proposal) / (share * mean weight), as
  // w <= 1 / share.
  const double bound_proposal = 1 - std::pow(0.05, 1 / n);
  const double mean_weight = normalised ? total / n : 1.0;
  const double upper_bound = std::min(1.0, bound_proposal / (share * mean_weight));
  for (const auto& [outcome, weight_and_count] : failed) {
    // Self-normalised, sum w 1F / sum w, with the delta method's variance; or, when the weights'
    // mean is known to be 1, the plain mean of w 1F with its sample variance.
    const double p = weight_and_count.first / (normalised ? total : n);
    OutcomeEstimate o{outcome, weight_and_count.second, p};
    double variance = 0;
    for (const WeightedOutcome& r : records) {
      const double f = r.outcome == outcome ? 1.0 : 0.0;
      variance += normalised ? r.weight * r.weight * (f - p) * (f - p)
                             : (r.weight * f - p) * (r.weight * f - p);
    }
    variance /= normalised ? total * total : n * (n - 1);
    variance *= CalcEdgeFactor(records, outcome);
    // The exact binomial interval at the effective counts (intervals.h): right for few
    // failures and for p near 1, where the delta method's p +- 1.96 sd is not.
    const RateInterval ci = CalcEffectiveCountInterval(std::min(p, 1.0), variance, estimate.ess);
    o.ci_low = ci.low;
    o.ci_high = ci.high;
    o.iid_episodes = variance > 0 ? o.p * (1 - o.p) / variance : estimate.ess;
    estimate.outcomes.push_back(o);
  }
  std::stable_sort(estimate.outcomes.begin(), estimate.outcomes.end(),
                   [](const auto& a, const auto& b) { return a.p > b.p; });
  // Failure kinds seen elsewhere (an adaptation's episodes) but not here: a row with the bound.
  std::set<std::string> unseen(also_seen.begin(), also_seen.end());
  unseen.erase("success");
  for (const auto& [outcome, ignored] : failed) unseen.erase(outcome);
  for (const std::string& outcome : unseen) {
    estimate.outcomes.push_back({outcome, 0, 0, 0, upper_bound, 0});
  }
  if (failed.empty()) estimate.upper_bound = upper_bound;
  return estimate;
}

WeightedRecords SelectWeightedRecords(const std::vector<ReportRecord>& records,
                                      const std::string& path, const std::string& spec_hash) {
  WeightedRecords weighted, plain;
  std::set<std::string> seen;
  const ReportRecord* refused = nullptr;  // the first record whose law gives no estimate
  for (const ReportRecord& record : records) {
    if (!spec_hash.empty() && !record.spec.empty() && record.spec != spec_hash) {
      throw std::runtime_error(fmt::format(
          "{}:{}: the record was drawn from another program (fingerprint \"{}\", this one's "
          "\"{}\")",
          path, record.line, record.spec, spec_hash));
    }
    seen.insert(record.outcome);
    const RecordLaw law = DescribeLaw(record);
    if (law == RecordLaw::kImportance) {
      weighted.records.push_back({record.outcome, record.weight, record.uniform_share,
                                  record.normalised, record.score.value_or(NAN),
                                  record.kernel_share});
    } else if (law == RecordLaw::kIid) {
      plain.records.push_back({record.outcome});
    } else if (law != RecordLaw::kSearch) {
      // A chain's, a design's or a replay of failures: never an estimate, whatever else the
      // file holds. A search's records beside weighted ones are an estimate's adaptation.
      throw std::runtime_error(fmt::format(
          "{}:{}: {} give no estimate of how often the controller fails under the program's "
          "law: {}",
          path, record.line, DescribeLawInWords(law),
          law == RecordLaw::kSelected
              ? "estimate from the records it replays, or replay them all (without --failed)"
          : law == RecordLaw::kChain ? "run prs test without --sampler gibbs, or prs estimate"
                                     : "run prs test without --design, or prs estimate"));
    } else if (!refused) {
      refused = &record;
    }
  }
  WeightedRecords& chosen = !weighted.records.empty() ? weighted : plain;
  if (chosen.records.empty()) {
    throw std::runtime_error(
        refused ? fmt::format("{}:{}: {} holds only {}: estimate with `prs estimate`, whose "
                              "records carry weights",
                              path, refused->line, path, DescribeLawInWords(RecordLaw::kSearch))
                : path + " holds no record");
  }
  chosen.outcomes_seen.assign(seen.begin(), seen.end());
  return chosen;
}

WeightedRecords ReadWeightedRecords(const std::vector<std::string>& lines, const std::string& path,
                                    const std::string& spec_hash) {
  return SelectWeightedRecords(ParseReportRecords(lines, path), path, spec_hash);
}

}  // namespace prs::search
