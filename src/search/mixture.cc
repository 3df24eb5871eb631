// The defensive mixture's density and its points (mixture.h).
#include "search/mixture.h"

#include <algorithm>
#include <cmath>

#include "geometry/random.h"
#include "search/like.h"

namespace prs::search {
namespace {

// The normal CDF.
double CalcNormalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

// The density at x of the normal (mean, std) truncated to [0, 1].
double CalcTruncatedNormalDensity(double x, double mean, double std) {
  const double mass = CalcNormalCdf((1 - mean) / std) - CalcNormalCdf(-mean / std);
  if (!(mass > 0)) return 1;  // MixturePoints then draws this coordinate uniformly
  const double z = (x - mean) / std;
  return std::exp(-0.5 * z * z) / (std::sqrt(2 * M_PI) * std * mass);
}

}  // namespace

double MixtureProposal::CalcDensity(const double* u) const {
  if (uniform_share >= 1) return 1;
  // The normals around `centre` with spread `spread` times `factor`, on the coordinates
  // with std > 0.
  auto normals = [&](const std::vector<double>& centre, const std::vector<double>& spread,
                     double factor) {
    double density = 1;
    for (int j = 0; j < dimension(); ++j) {
      if (std[j] > 0) density *= CalcTruncatedNormalDensity(u[j], centre[j], factor * spread[j]);
    }
    return density;
  };
  auto layers = [&](const std::vector<double>& centre, const std::vector<double>& spread) {
    if (wide_share <= 0) return normals(centre, spread, 1);
    return (1 - wide_share) * normals(centre, spread, 1) +
           wide_share * normals(centre, spread, wide_factor);
  };
  double gaussian = 0;
  if (centres.empty()) {
    gaussian = layers(mean, std);
  } else {
    for (size_t i = 0; i < centres.size(); ++i) {
      gaussian += layers(centres[i], centre_std.empty() ? std : centre_std[i]);
    }
    gaussian /= double(centres.size());
  }
  return uniform_share + (1 - uniform_share) * gaussian;
}

double MixtureProposal::CalcKernelShare(const double* u) const {
  if (uniform_share >= 1) return 0;
  const double density = CalcDensity(u);
  return (density - uniform_share) / density;
}

bool MixturePoints::Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const {
  geometry::Rng rng = MakeProposalRng(seed, index, attempt);
  const int d = dimension();
  if (proposal_.uniform_share >= 1 || rng.Uniform01() < proposal_.uniform_share) {
    for (int j = 0; j < d; ++j) u[j] = rng.Uniform01();
    return true;
  }
  const size_t pick = proposal_.centres.empty()
                          ? 0
                          : size_t(rng.UniformInt(0, int64_t(proposal_.centres.size()) - 1));
  const std::vector<double>& centre =
      proposal_.centres.empty() ? proposal_.mean : proposal_.centres[pick];
  const std::vector<double>& spread =
      proposal_.centre_std.empty() ? proposal_.std : proposal_.centre_std[pick];
  // The wide layer's draw only when there is one, so that the points of a mixture without it
  // are those of earlier versions.
  const double factor = proposal_.wide_share > 0 && rng.Uniform01() < proposal_.wide_share
                            ? proposal_.wide_factor
                            : 1.0;
  for (int j = 0; j < d; ++j) {
    const double v = rng.Uniform01();
    if (proposal_.std[j] <= 0) {
      u[j] = v;
      continue;
    }
    const double x = geometry::MapTruncatedNormal(v, centre[j], factor * spread[j], 0, 1);
    u[j] = std::isnan(x) ? rng.Uniform01() : std::min(x, 1.0 - 0x1.0p-53);
  }
  return true;
}

}  // namespace prs::search
