// Fitting and drawing the failures' proposal, reading failures back from records, and the
// program fingerprint.
#include "search/like.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "geometry/random.h"

namespace prs::search {
namespace {

constexpr double kLikeUniformShare = 0.05;

constexpr uint64_t kProposalSalt = 0x5EA2C4E1B0F3A977ULL;

// One line as an episode record (a JSON object with an "outcome" string), or a located error.
nlohmann::json ParseRecord(const std::string& line, const std::string& where) {
  auto record = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
  if (!record.is_object() || !record.contains("outcome") || !record["outcome"].is_string()) {
    throw std::runtime_error(where +
                             ": not an episode record (a JSON object with an "
                             "\"outcome\"); give the -o file of prs search or prs test");
  }
  return record;
}

// The record's coordinates, checked against the program; nullopt when it has none.
std::optional<std::vector<double>> CheckCoordinates(const nlohmann::json& record,
                                                    const std::string& where,
                                                    const std::string& spec_hash, int dimension) {
  const auto coordinates = record.find("coordinates");
  if (coordinates == record.end()) return std::nullopt;
  const auto spec = record.find("spec");
  if (spec == record.end() || !spec->is_string()) {
    throw std::runtime_error(where +
                             ": the record has coordinates but no \"spec\" hash, so "
                             "it cannot be tied to this program");
  }
  if (spec->get<std::string>() != spec_hash) {
    throw std::runtime_error(where + ": the record was written for another program (spec " +
                             spec->get<std::string>() + ", this one is " + spec_hash +
                             "); give the same FILE, -I and -p as the run that wrote it");
  }
  if (!coordinates->is_array() || static_cast<int>(coordinates->size()) != dimension ||
      !std::all_of(coordinates->begin(), coordinates->end(), [](const nlohmann::json& x) {
        return x.is_number() && x.get<double>() >= 0 && x.get<double>() < 1;
      })) {
    throw std::runtime_error(fmt::format(
        "{}: \"coordinates\" must be {} numbers of [0, 1) for this program", where, dimension));
  }
  return coordinates->get<std::vector<double>>();
}

}  // namespace

uint64_t CalcFnv1a(std::string_view bytes, uint64_t hash) {
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001B3ULL;
  }
  return hash;
}

geometry::Rng MakeProposalRng(uint64_t seed, uint64_t index, int64_t attempt) {
  return geometry::Rng(
      seed ^ kProposalSalt ^ (static_cast<uint64_t>(attempt) * 0x9E3779B97F4A7C15ULL), index);
}

std::string CalcSpecHash(const lang::CompiledProgram& program) {
  uint64_t hash = kFnv1aOffset;
  for (size_t f = 0; f < program.sources.file_count(); ++f) {
    hash = CalcFnv1a(program.sources.text(static_cast<lang::FileId>(f)), hash);
    hash = CalcFnv1a(std::string_view("\0", 1), hash);
  }
  std::map<std::string, std::string> params(program.param_overrides.begin(),
                                            program.param_overrides.end());
  for (const auto& [name, value] : params) hash = CalcFnv1a(name + "=" + value + ";", hash);
  // The URDF files its arms name shape its scenes too (none: the hash is as it always was).
  for (const lang::ProgramResource& r : lang::ListResources(program)) {
    hash = CalcFnv1a(r.name + "\n" + r.text + std::string("\0", 1), hash);
  }
  return fmt::format("{:016x}", hash);
}

GaussianPoints::GaussianPoints(std::vector<double> mean, std::vector<double> std,
                               double uniform_share)
    : mean_(std::move(mean)), std_(std::move(std)), uniform_share_(uniform_share) {}

bool GaussianPoints::Point(uint64_t seed, uint64_t index, int64_t attempt, double* u) const {
  if (attempt >= kMaxProposalAttempts) return false;
  geometry::Rng rng = MakeProposalRng(seed, index, attempt);
  const int d = dimension();
  if (rng.Uniform01() < uniform_share_) {
    for (int j = 0; j < d; ++j) u[j] = rng.Uniform01();
    return true;
  }
  for (int j = 0; j < d; ++j) {
    const double x = geometry::MapTruncatedNormal(rng.Uniform01(), mean_[j], std_[j], 0, 1);
    u[j] = std::isnan(x) ? rng.Uniform01() : std::min(x, 1.0 - 0x1.0p-53);
  }
  return true;
}

FailureSet ReadFailures(const std::vector<std::string>& lines, const std::string& path,
                        const std::string& outcome, const std::string& spec_hash, int dimension) {
  FailureSet set;
  std::map<std::string, int64_t> outcomes;
  int64_t with_coordinates = 0;
  for (size_t n = 0; n < lines.size(); ++n) {
    const std::string& line = lines[n];
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = fmt::format("{}:{}", path, n + 1);
    const nlohmann::json record = ParseRecord(line, where);
    ++set.records;
    const std::string name = record["outcome"].get<std::string>();
    ++outcomes[name];
    const std::optional<std::vector<double>> coordinates =
        CheckCoordinates(record, where, spec_hash, dimension);
    if (!coordinates) continue;
    ++with_coordinates;
    const bool selected = outcome.empty() ? name != "success" : name == outcome;
    if (selected) set.coordinates.push_back(*coordinates);
  }
  if (with_coordinates == 0) {
    throw std::runtime_error(path +
                             ": no record has scene coordinates; write records with "
                             "prs search -o, or prs test --design sobol -o");
  }
  if (set.coordinates.empty()) {
    std::string found;
    for (const auto& [name, n] : outcomes) {
      found += fmt::format("{}{} {}", found.empty() ? "" : ", ", name, n);
    }
    throw std::runtime_error(
        path + ": no record with " +
        (outcome.empty() ? std::string("a failing outcome") : "the outcome '" + outcome + "'") +
        " (outcomes: " + found + ")");
  }
  return set;
}

std::vector<double> ReadRecordCoordinates(const std::vector<std::string>& lines,
                                          const std::string& path, int64_t line,
                                          const std::string& spec_hash, int dimension) {
  if (line == 0) {
    return ReadFailures(lines, path, "", spec_hash, dimension).coordinates.front();
  }
  if (line < 0 || line > static_cast<int64_t>(lines.size())) {
    throw std::runtime_error(
        fmt::format("{}: has {} lines; there is no line {}", path, lines.size(), line));
  }
  const std::string where = fmt::format("{}:{}", path, line);
  const auto record = ParseRecord(lines[line - 1], where);
  std::optional<std::vector<double>> coordinates =
      CheckCoordinates(record, where, spec_hash, dimension);
  if (!coordinates) {
    throw std::runtime_error(where +
                             ": the record has no scene coordinates; write records with "
                             "prs search -o, or prs test --design sobol -o");
  }
  return *coordinates;
}

GaussianPoints FitLike(const FailureSet& failures) {
  const size_t d = failures.coordinates.front().size();
  const double n = static_cast<double>(failures.coordinates.size());
  std::vector<double> mean(d, 0), std(d, 0);
  for (const auto& u : failures.coordinates) {
    for (size_t j = 0; j < d; ++j) mean[j] += u[j] / n;
  }
  for (const auto& u : failures.coordinates) {
    for (size_t j = 0; j < d; ++j) std[j] += (u[j] - mean[j]) * (u[j] - mean[j]) / n;
  }
  for (double& s : std) s = std::max(kMinProposalStd, std::sqrt(s));
  return GaussianPoints(mean, std, kLikeUniformShare);
}

}  // namespace prs::search
