// What `prs estimate` and an estimate campaign's merge print: one row per failure outcome with
// its 95 % interval, or the --json object, and what the estimate means (unreliable, a bound).
#pragma once

#include <string>

#include "search/estimate.h"

namespace prs::cli {

/// outcome / p / 95% interval / failed / i.i.d. episodes for as tight, one row per outcome.
std::string FormatEstimateTable(const search::Estimate& e);

/// The --json object: {"episodes", "ess", "reliable", "estimates": {...}, "upper_bound_95"}.
std::string FormatEstimateJson(const search::Estimate& e);

/// Prints the estimate (the table, or JSON with `json`) on stdout and what it means on stderr
/// (notes left out with `quiet`); returns the exit code.
int PrintEstimate(const search::Estimate& e, bool json, bool quiet);

}  // namespace prs::cli
