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

/// When generations of `batch` episodes leave `threads` workers idle for more than a tenth of
/// each generation (its last wave is short: 20 on 16 threads keeps 16 busy, then 4), the note
/// that says so and names the next batch that keeps every thread busy; "" otherwise. A
/// generation ends before the next begins, so its last wave's idle threads wait for it.
std::string FormatBatchUseNote(int64_t batch, int threads);

/// index / name / draw / source, one row per scene coordinate.
std::string FormatCoordinateTable(const std::vector<lang::CoordinateInfo>& coordinates,
                                  const lang::SourceManager& sources);

}  // namespace prs::cli
