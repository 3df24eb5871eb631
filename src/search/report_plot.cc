// The failure report's scatter plot, written as SVG text by hand: a few dozen elements, where a
// plotting library (matplotlib, gnuplot) would be a run-time dependency of the CLI for one
// picture.
#include "search/report_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace prs::search {
namespace {

// Layout, in SVG pixels.
constexpr double kWidth = 720, kHeight = 540;
constexpr double kLeft = 84, kRight = 24, kTop = 72, kBottom = 64;
constexpr double kPlotWidth = kWidth - kLeft - kRight, kPlotHeight = kHeight - kTop - kBottom;
constexpr const char* kFailureColour = "#d62728";
constexpr const char* kSuccessColour = "#b0b0b0";
constexpr const char* kSplitColour = "#1f4e9c";

std::string EscapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// An axis's name: the feature's, with its unit (features are in metres and radians; scene
// coordinates have none).
std::string NameAxis(const std::string& feature) {
  const auto ends_with = [&](const char* suffix) {
    const std::string s = suffix;
    return feature.size() > s.size() &&
           feature.compare(feature.size() - s.size(), s.size(), s) == 0;
  };
  std::string unit;
  if (ends_with(".yaw")) {
    unit = " (rad)";
  } else if (ends_with(".x") || ends_with(".y") || ends_with(".z") ||
             feature.rfind("dist(", 0) == 0) {
    unit = " (m)";
  }
  return EscapeXml(feature) + unit;
}

// The range of a feature over the rows where both plotted features are known, widened by 3 %
// on each side so that no point sits on the frame (a constant feature gets a unit range).
std::pair<double, double> CalcAxisRange(const FeatureTable& table, int f, int other) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& row : table.rows) {
    if (std::isnan(row[f]) || std::isnan(row[other])) continue;
    lo = std::min(lo, row[f]);
    hi = std::max(hi, row[f]);
  }
  if (!std::isfinite(lo)) return {0, 1};
  if (!(hi > lo)) return {lo - 0.5, lo + 0.5};
  const double pad = 0.03 * (hi - lo);
  return {lo - pad, hi + pad};
}

}  // namespace

std::vector<double> CalcAxisTicks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  target = std::max(2, target);
  const auto ticks_of = [&](double step) {
    std::vector<double> ticks;
    const auto first = static_cast<int64_t>(std::ceil(lo / step - 1e-9));
    const auto last = static_cast<int64_t>(std::floor(hi / step + 1e-9));
    for (int64_t k = first; k <= last; ++k) {
      const double value = static_cast<double>(k) * step;  // no accumulated rounding
      if (value >= lo - 1e-9 * step && value <= hi + 1e-9 * step) ticks.push_back(value);
    }
    return ticks;
  };
  // The round steps around range / target; the one whose tick count is nearest the target
  // (the larger step on a tie).
  const double magnitude = std::pow(10.0, std::floor(std::log10((hi - lo) / target)));
  std::vector<double> best;
  for (double m : {10.0, 5.0, 2.0, 1.0, 0.5}) {
    std::vector<double> ticks = ticks_of(m * magnitude);
    if (best.empty() || std::abs(static_cast<int>(ticks.size()) - target) <
                            std::abs(static_cast<int>(best.size()) - target)) {
      best = std::move(ticks);
    }
  }
  return best;
}

std::string FormatTick(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  if (std::fabs(value) < 1e-9 * step) value = 0;  // never "-0"
  return fmt::format("{:.{}f}", value, decimals);
}

bool AreRedundant(const FeatureTable& table, int a, int b) {
  if (a == b) return true;
  std::vector<std::pair<double, double>> values;  // (a, b) where both are known
  for (const auto& row : table.rows) {
    if (!std::isnan(row[a]) && !std::isnan(row[b])) values.emplace_back(row[a], row[b]);
  }
  const size_t n = values.size();
  if (n < 3) return true;
  double mean_a = 0, mean_b = 0;
  for (const auto& [x, y] : values) {
    mean_a += x;
    mean_b += y;
  }
  mean_a /= static_cast<double>(n);
  mean_b /= static_cast<double>(n);
  double var_a = 0, var_b = 0, cov = 0;
  for (const auto& [x, y] : values) {
    var_a += (x - mean_a) * (x - mean_a);
    var_b += (y - mean_b) * (y - mean_b);
    cov += (x - mean_a) * (y - mean_b);
  }
  var_a /= static_cast<double>(n);
  var_b /= static_cast<double>(n);
  cov /= static_cast<double>(n);
  if (!(var_a > 0) || !(var_b > 0)) return true;
  constexpr double kMaxCorrelation = 0.99;
  if (std::fabs(cov) > kMaxCorrelation * std::sqrt(var_a * var_b)) return true;
  // Is `other` nearly a function of `key`? Sorted by key, successive values of independent
  // features differ by 2·var on average (squared); for other = k·key + noise by 2·var·(1 - r²).
  // Only steps between distinct keys count (the order within ties says nothing), and at least
  // 10 of them.
  const auto nearly_a_function = [&](bool b_of_a) {
    std::vector<std::pair<double, double>> sorted;  // (key, other)
    sorted.reserve(n);
    for (const auto& [x, y] : values) sorted.emplace_back(b_of_a ? x : y, b_of_a ? y : x);
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& p, const auto& q) { return p.first < q.first; });
    double squares = 0;
    int64_t steps = 0;
    for (size_t i = 0; i + 1 < n; ++i) {
      if (!(sorted[i + 1].first > sorted[i].first)) continue;
      const double step = sorted[i + 1].second - sorted[i].second;
      squares += step * step;
      ++steps;
    }
    if (steps < 10) return false;
    const double var = b_of_a ? var_b : var_a;
    return squares / static_cast<double>(steps) < 2 * (1 - kMaxCorrelation * kMaxCorrelation) * var;
  };
  return nearly_a_function(true) || nearly_a_function(false);
}

int ChooseSecondPlotFeature(const FeatureTable& table, const std::vector<bool>& failed,
                            const std::vector<Split>& splits) {
  if (splits.empty()) return -1;
  const Split& top = splits.front();
  const int features = static_cast<int>(table.names.size());
  // The candidates: the ranked features, then the others in the table's order.
  std::vector<int> candidates;
  std::vector<bool> listed(table.names.size(), false);
  for (const Split& s : splits) {
    if (!listed[s.feature]) candidates.push_back(s.feature);
    listed[s.feature] = true;
  }
  for (int f = 0; f < features; ++f) {
    if (!listed[f]) candidates.push_back(f);
  }
  // The two sides of the strongest split (an unknown value goes below, as in GrowTree).
  std::vector<size_t> sides[2];
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const double v = table.rows[r][top.feature];
    sides[std::isnan(v) || v <= top.threshold ? 0 : 1].push_back(r);
  }
  const int64_t n = static_cast<int64_t>(table.rows.size());
  const int64_t min_leaf = std::max<int64_t>(5, n / 50);  // as the report's depth-2 tree
  int best = -1, fallback = -1;
  double best_gain = 0;
  for (const int f : candidates) {
    if (AreRedundant(table, top.feature, f)) continue;
    if (fallback < 0) fallback = f;
    double gain = 0;  // of the best split of f on each side, weighted by the side's share
    for (const std::vector<size_t>& side : sides) {
      FeatureTable one{{table.names[f]}, {}};
      std::vector<bool> one_failed;
      one.rows.reserve(side.size());
      for (size_t r : side) {
        one.rows.push_back({table.rows[r][f]});
        one_failed.push_back(failed[r]);
      }
      const TreeNode node = GrowTree(one, one_failed, 1, min_leaf);
      if (node.split) gain += static_cast<double>(side.size()) / n * node.split->gain;
    }
    if (gain > best_gain + 1e-12) {
      best = f;
      best_gain = gain;
    }
  }
  return best >= 0 ? best : fallback;
}

std::string FormatScatterSvg(const FeatureTable& table, const std::vector<bool>& failed, int fx,
                             int fy, const Split* split) {
  const auto [x_lo, x_hi] = CalcAxisRange(table, fx, fy);
  const auto [y_lo, y_hi] = CalcAxisRange(table, fy, fx);
  auto px = [&, x_lo = x_lo, x_hi = x_hi](double x) {
    return kLeft + (x - x_lo) / (x_hi - x_lo) * kPlotWidth;
  };
  auto py = [&, y_lo = y_lo, y_hi = y_hi](double y) {
    return kTop + kPlotHeight - (y - y_lo) / (y_hi - y_lo) * kPlotHeight;
  };
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      kWidth, kHeight);

  // The failure-rich side of the split, shaded under everything else.
  const bool draw_split = split != nullptr && split->feature == fx;
  const double split_x = draw_split ? px(split->threshold) : 0;
  if (draw_split) {
    const double from = split->failures_below ? kLeft : split_x;
    const double to = split->failures_below ? split_x : kLeft + kPlotWidth;
    svg += fmt::format(
        "<rect class=\"failure-side\" x=\"{:.1f}\" y=\"{}\" width=\"{:.1f}\" height=\"{}\" "
        "fill=\"{}\" fill-opacity=\"0.07\"/>\n",
        from, kTop, to - from, kPlotHeight, kFailureColour);
  }

  // Grid lines, ticks and their values.
  const std::vector<double> x_ticks = CalcAxisTicks(x_lo, x_hi);
  const std::vector<double> y_ticks = CalcAxisTicks(y_lo, y_hi);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
  for (double t : x_ticks) {
    const double x = px(t);
    svg += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#e6e6e6\"/>\n"
        "<line x1=\"{0:.1f}\" y1=\"{2}\" x2=\"{0:.1f}\" y2=\"{3}\" stroke=\"black\"/>\n"
        "<text class=\"x-tick\" x=\"{0:.1f}\" y=\"{4}\" text-anchor=\"middle\">{5}</text>\n",
        x, kTop, kTop + kPlotHeight, kTop + kPlotHeight + 5, kTop + kPlotHeight + 19,
        FormatTick(t, x_step));
  }
  for (double t : y_ticks) {
    const double y = py(t);
    svg += fmt::format(
        "<line x1=\"{1}\" y1=\"{0:.1f}\" x2=\"{2}\" y2=\"{0:.1f}\" stroke=\"#e6e6e6\"/>\n"
        "<line x1=\"{3}\" y1=\"{0:.1f}\" x2=\"{1}\" y2=\"{0:.1f}\" stroke=\"black\"/>\n"
        "<text class=\"y-tick\" x=\"{4}\" y=\"{0:.1f}\" dy=\"0.35em\" "
        "text-anchor=\"end\">{5}</text>\n",
        y, kLeft, kLeft + kPlotWidth, kLeft - 5, kLeft - 8, FormatTick(t, y_step));
  }
  svg += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n",
      kLeft, kTop, kPlotWidth, kPlotHeight);

  // The points: successes first, so that failures are drawn on top.
  int64_t counts[2] = {0, 0};
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t r = 0; r < table.rows.size(); ++r) {
      if (failed[r] != (pass == 1)) continue;
      const auto& row = table.rows[r];
      if (std::isnan(row[fx]) || std::isnan(row[fy])) continue;
      ++counts[pass];
      svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.5\" fill=\"{}\"/>\n",
                         px(row[fx]), py(row[fy]), pass == 1 ? kFailureColour : kSuccessColour);
    }
  }

  // The split's line and what it says, on the line's wider side.
  if (draw_split) {
    const bool label_left = split_x - kLeft > kLeft + kPlotWidth - split_x;  // the wider side
    svg += fmt::format(
        "<line class=\"split\" x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" "
        "stroke=\"{3}\" stroke-width=\"2\"/>\n"
        "<text x=\"{4:.1f}\" y=\"{5}\" fill=\"{3}\" text-anchor=\"{6}\" stroke=\"white\" "
        "stroke-width=\"4\" paint-order=\"stroke\">{7} {8} {9}: {10} of {11} fail</text>\n",
        split_x, kTop, kTop + kPlotHeight, kSplitColour, split_x + (label_left ? -6 : 6), kTop + 16,
        label_left ? "end" : "start", EscapeXml(table.names[fx]),
        split->failures_below ? "≤" : "&gt;", fmt::format("{:.4g}", split->threshold),
        split->failures_side, split->n_side);
  }

  // Axis names.
  svg += fmt::format(
      "<text class=\"x-name\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"13\">{}</text>\n"
      "<text class=\"y-name\" x=\"18\" y=\"{}\" text-anchor=\"middle\" font-size=\"13\" "
      "transform=\"rotate(-90 18 {})\">{}</text>\n",
      kLeft + kPlotWidth / 2, kHeight - 14, NameAxis(table.names[fx]), kTop + kPlotHeight / 2,
      kTop + kPlotHeight / 2, NameAxis(table.names[fy]));

  // The title and the legend, above the plot.
  svg += fmt::format(
      "<text x=\"{0}\" y=\"24\" font-size=\"14\" font-weight=\"bold\">The two features that best "
      "separate failures from successes</text>\n"
      "<g class=\"legend\">\n"
      "<circle cx=\"{1}\" cy=\"48\" r=\"4\" fill=\"{2}\"/><text x=\"{3}\" y=\"52\">failure "
      "({4})</text>\n"
      "<circle cx=\"{5}\" cy=\"48\" r=\"4\" fill=\"{6}\"/><text x=\"{7}\" y=\"52\">success "
      "({8})</text>\n",
      kLeft, kLeft + 4, kFailureColour, kLeft + 12, counts[1], kLeft + 124, kSuccessColour,
      kLeft + 132, counts[0]);
  if (draw_split) {
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"48\" x2=\"{1}\" y2=\"48\" stroke=\"{2}\" stroke-width=\"2\"/>"
        "<rect x=\"{3}\" y=\"41\" width=\"14\" height=\"14\" fill=\"{4}\" fill-opacity=\"0.07\" "
        "stroke=\"#dddddd\"/><text x=\"{5}\" y=\"52\">strongest split; shaded: its failure-rich "
        "side</text>\n",
        kLeft + 244, kLeft + 264, kSplitColour, kLeft + 270, kFailureColour, kLeft + 290);
  }
  svg += "</g>\n</svg>\n";
  return svg;
}

}  // namespace prs::search
