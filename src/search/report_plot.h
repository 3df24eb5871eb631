// The failure report's picture (docs/search.md, "Failure reports"): a scatter plot of the
// strongest split's feature against the one that best separates failures on each side of it,
// never one that is a function of the first, with axes a person reads (tick values, names, units
// as recorded), the strongest split drawn as a line over the failure-rich side, and a legend.
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

/// True when the two features carry the same information for a picture: over the rows where
/// both are known (fewer than 3: true), either is constant, their correlation |r| exceeds 0.99
/// (an affine function of the other, as Cube-t.x is of Cube.x when the table is fixed), or
/// either is nearly a function of the other (sorted by one, the other's successive values
/// differ by less than 1 - 0.99² of its spread: a distance that grows with an offset). Plotted
/// against each other, such features draw a curve, not where failures are.
bool AreRedundant(const FeatureTable& table, int a, int b);

/// The scatter plot's vertical feature, to draw against the strongest split's feature
/// (splits[0], the horizontal one): among the features not redundant with it (AreRedundant),
/// the one whose best split on each side of that split gains the most information — the
/// second level of a depth-2 tree over the two features, so a failure that needs both (x > 0.8
/// and y > 0.3) shows as a corner. With no gain anywhere, the best ranked such feature; ties go
/// to the better ranked one. -1 when `splits` is empty or every feature is redundant with the
/// first.
int ChooseSecondPlotFeature(const FeatureTable& table, const std::vector<bool>& failed,
                            const std::vector<Split>& splits);

/// The scatter plot (SVG text) of features fx (horizontal) and fy (vertical): successes grey,
/// failures red on top, with tick values on both axes, each axis named with its unit, a legend with
/// the counts, and, when `split` is given and is a split of fx, its threshold as a vertical line
/// with the failure-rich side shaded, and labelled on its wider side ("Cube.x ≤ -0.75: 120 of
/// 130 fail").
std::string FormatScatterSvg(const FeatureTable& table, const std::vector<bool>& failed, int fx,
                             int fy, const Split* split);

}  // namespace prs::search
