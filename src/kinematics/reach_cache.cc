// The reachable sets' disk cache (see reach.h): one text file per key with the cells'
// half-spaces at %.17g, written to a temporary file and renamed into place; a file that does
// not parse or was written for another key is recomputed, never fatal.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "kinematics/reach_internal.h"

namespace prs::kinematics {

namespace internal {

namespace {

constexpr const char* kMagic = "prs-reach-cache";

std::string FormatDouble(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

std::string FormatReachFile(const ReachableSet& set) {
  std::string text =
      std::string(kMagic) + " " + std::to_string(kReachFormatVersion) + " " + set.key + "\n";
  text += "cells " + std::to_string(set.cells_Base.size()) + "\n";
  for (size_t c = 0; c < set.cells_Base.size(); ++c) {
    const auto& half_spaces = set.cells_Base[c].half_spaces();
    text += "cell " + std::to_string(half_spaces.size()) + " " +
            FormatDouble(set.cell_volumes_m3[c]) + "\n";
    for (const geometry::HalfSpace& h : half_spaces) {
      text += FormatDouble(h.normal.x()) + " " + FormatDouble(h.normal.y()) + " " +
              FormatDouble(h.normal.z()) + " " + FormatDouble(h.offset) + "\n";
    }
  }
  const ReachStats& s = set.stats;
  text += "stats " + std::to_string(s.symmetric) + " " + std::to_string(s.grid_nodes) + " " +
          std::to_string(s.nodes_tested) + " " + std::to_string(s.nodes_reachable) + " " +
          std::to_string(s.ik_iterations) + " " + FormatDouble(s.seconds) + "\n";
  text += "volume " + FormatDouble(set.volume_m3) + "\nend\n";
  return text;
}

bool ParseReachFile(const std::string& text, const std::string& key, ReachableSet* set,
                    std::string* problem) {
  std::istringstream in(text);
  std::string word, file_key;
  int version = 0;
  if (!(in >> word >> version >> file_key) || word != kMagic) {
    return *problem = "not a reachable-set cache file", false;
  }
  if (version != kReachFormatVersion || file_key != key) {
    return *problem = "written for another arm, options or format (version " +
                      std::to_string(version) + ", key " + file_key + ")",
           false;
  }
  ReachableSet loaded;
  loaded.key = key;
  size_t cells = 0;
  if (!(in >> word >> cells) || word != "cells") return *problem = "no cell count", false;
  for (size_t c = 0; c < cells; ++c) {
    size_t count = 0;
    double volume = 0;
    if (!(in >> word >> count >> volume) || word != "cell" || count > 64 || !(volume > 0)) {
      return *problem = "cell " + std::to_string(c) + " is malformed", false;
    }
    std::vector<geometry::HalfSpace> half_spaces(count);
    for (geometry::HalfSpace& h : half_spaces) {
      if (!(in >> h.normal.x() >> h.normal.y() >> h.normal.z() >> h.offset) ||
          !h.normal.allFinite() || !std::isfinite(h.offset) ||
          std::abs(h.normal.norm() - 1) > 1e-9) {
        return *problem = "cell " + std::to_string(c) + " has a malformed half-space", false;
      }
    }
    loaded.cells_Base.push_back(geometry::ConvexRegion::FromHalfSpaces(half_spaces));
    loaded.cell_volumes_m3.push_back(volume);
  }
  ReachStats& s = loaded.stats;
  if (!(in >> word >> s.symmetric >> s.grid_nodes >> s.nodes_tested >> s.nodes_reachable >>
        s.ik_iterations >> s.seconds) ||
      word != "stats") {
    return *problem = "the statistics line is malformed", false;
  }
  if (!(in >> word >> loaded.volume_m3) || word != "volume" || !(in >> word) || word != "end") {
    return *problem = "the file is truncated", false;
  }
  *set = std::move(loaded);
  return true;
}

}  // namespace internal

namespace {

namespace fs = std::filesystem;

// Writes `text` to `path` by a rename from a temporary file beside it. Returns "" or why not.
std::string WriteAtomically(const fs::path& path, const std::string& text) {
  static std::atomic<int> counter{0};
  std::error_code error;
  fs::create_directories(path.parent_path(), error);
  if (error) return "cannot create " + path.parent_path().string() + ": " + error.message();
  const fs::path temporary = path.string() + ".tmp." + std::to_string(getpid()) + "." +
                             std::to_string(counter.fetch_add(1));
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      fs::remove(temporary, error);
      return "cannot write " + temporary.string();
    }
  }
  fs::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return "cannot rename " + temporary.string() + " to " + path.string() + ": " + error.message();
  }
  return "";
}

bool ReadFile(const fs::path& path, std::string* text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  *text = buffer.str();
  return !in.bad();
}

}  // namespace

ReachLoad LoadOrComputeReachableSet(const Chain& chain, const ReachOptions& options,
                                    const std::string& cache_dir) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  ReachLoad load;
  if (!cache_dir.empty()) {
    const std::string key = CalcReachKey(chain, options);
    const fs::path path = fs::path(cache_dir) / ("reach-" + key + ".txt");
    std::string text, problem;
    if (ReadFile(path, &text)) {
      auto set = std::make_shared<ReachableSet>();
      if (internal::ParseReachFile(text, key, set.get(), &problem)) {
        for (const geometry::ConvexRegion& cell : set->cells_Base) cell.Finalize();
        load.set = std::move(set);
        load.from_cache = true;
        load.seconds = elapsed();
        return load;
      }
      load.warning = "ignored the reachable-set cache file " + path.string() + " (" + problem + ")";
    }
    auto set = std::make_shared<ReachableSet>(ComputeReachableSet(chain, options));
    const std::string why = WriteAtomically(path, internal::FormatReachFile(*set));
    if (!why.empty()) {
      load.warning += (load.warning.empty() ? "" : "; ") +
                      std::string("could not write the reachable-set cache: ") + why;
    }
    load.set = std::move(set);
  } else {
    load.set = std::make_shared<ReachableSet>(ComputeReachableSet(chain, options));
  }
  load.seconds = elapsed();
  return load;
}

}  // namespace prs::kinematics
