// The text `prs check` prints: a header, the creation sites with their position regions, the
// properties observed to vary between sampled scenes, and the classes.
#pragma once

#include <string>

#include "analysis/property_variation.h"
#include "analysis/scenario_outline.h"

namespace prs::cli {

// The outline and the variation are computed in prs_analysis (shared with the Python package).
using analysis::ClassOutline;
using analysis::CreationSite;
using analysis::OutlineScenario;
using analysis::ScenarioOutline;
using analysis::SiteVariation;
using analysis::VariationObserver;

/// "FILE: VERDICT (M modules, C classes, S creation sites)", e.g. VERDICT "ok, 20 scenes sampled".
std::string FormatCheckHeader(const std::string& file, const std::string& verdict,
                              const lang::CompiledProgram& program, const ScenarioOutline& outline);

/// One row per creation site: where, variable, class, position specifiers, region kind.
std::string FormatObjectsSection(const ScenarioOutline& outline,
                                 const lang::SourceManager& sources);

/// One row per creation site: the properties that differed between the observed scenes.
std::string FormatRandomSection(const ScenarioOutline& outline, const VariationObserver& observed,
                                uint64_t seed, const lang::SourceManager& sources);

/// One row per class the program defines: parent, where, own properties.
std::string FormatClassesSection(const ScenarioOutline& outline,
                                 const lang::SourceManager& sources);

}  // namespace prs::cli
