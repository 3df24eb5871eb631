// The failure report's picture (docs/search.md, "Failure reports"): a scatter plot of the two
// most separating features with axes a person reads (tick values, names, units as recorded),
// the strongest split drawn as a line over the failure-rich side, and a legend.
#pragma once

#include <string>
#include <vector>

#include "search/report.h"

namespace prs::search {

/// Tick values for an axis over [lo, hi], in increasing order: the multiples inside [lo, hi]
/// of a step of 1, 2 or 5 times a power of ten, the step whose count of them is nearest
/// `target`.
std::vector<double> CalcAxisTicks(double lo, double hi, int target = 5);

/// A tick's label: as many decimals as the step needs, no more ("0.25", "-0.5", "1200").
std::string FormatTick(double value, double step);

/// The scatter plot (SVG text) of features fx (horizontal) and fy (vertical): successes grey,
/// failures red on top, with tick values on both axes, each axis named with its unit, a legend with
/// the counts, and, when `split` is given and is a split of fx, its threshold as a vertical line
/// with the failure-rich side shaded, and labelled on its wider side ("Cube.x ≤ -0.75: 120 of
/// 130 fail").
std::string FormatScatterSvg(const FeatureTable& table, const std::vector<bool>& failed, int fx,
                             int fy, const Split* split);

}  // namespace prs::search
