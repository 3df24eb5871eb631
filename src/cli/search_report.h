// What `prs search` prints: the search's progress by generation and its summary, and the
// coordinate list of `prs check --coordinates`.
#pragma once

#include <string>
#include <vector>

#include "lang/lang.h"
#include "search/search.h"

namespace prs::cli {

/// generation / episodes / failures / lowest score, one row per generation.
std::string FormatGenerationTable(const search::SearchSummary& summary);

/// "ce found 37 failures in 1000 episodes (3.7 %); the first at episode 212".
std::string FormatSearchVerdict(const search::SearchSummary& summary, search::Strategy strategy);

/// index / name / draw / source, one row per scene coordinate.
std::string FormatCoordinateTable(const std::vector<lang::CoordinateInfo>& coordinates,
                                  const lang::SourceManager& sources);

}  // namespace prs::cli
