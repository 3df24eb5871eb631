// `prs test` on saved scenes: a scenes file or a directory of them (--save-failures output) run
// as they are, or the records of an earlier run (`--replay RECORDS.jsonl`) regenerated from the
// program and checked against what they recorded (docs/harness.md, "Replaying saved scenes").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/harness.h"
#include "lang/lang.h"
#include "sampling/sampler.h"
#include "search/report.h"

namespace prs::cli {

/// One scene line of a scenes file, where it came from.
struct SavedSceneLine {
  std::string path;
  int64_t line = 0;  // 1-based
  std::string text;
  uint64_t seed = 0, index = 0;
};

/// The scenes of `path` (a scenes file, or a directory whose *.json and *.jsonl files are read
/// and whose scenes are then put in (seed, index) order), each line checked as scene JSON.
/// Nullopt after printing "FILE:LINE: what is wrong" (an episode record gets a pointer to
/// --replay), or that there is no scene.
std::optional<std::vector<SavedSceneLine>> ReadSavedScenes(const std::string& path);

/// Scenes of `lines` as they are (each worker reads them with a reader of its own); the
/// controller gets the line itself.
harness::ReplaySourceFactory MakeSavedSceneSources(const std::vector<SavedSceneLine>& lines);

/// The records of an earlier run to replay, checked against `program`: a record that names a
/// fingerprint (and every record drawn at coordinates) must name this program's, and one
/// that names its scene options must name `scene_options` (harness::SceneOptionsOf). Only
/// failures when `failed_only`. Nullopt after printing what is wrong.
std::optional<std::vector<search::ReportRecord>> ReadRecordsToReplay(
    const std::string& path, const lang::CompiledProgram& program,
    const std::string& scene_options, bool failed_only);

/// Scene (seed, index) of each record, at its coordinates when it has some (as the first
/// attempt), each checked against the record's features: a scene that differs throws
/// std::runtime_error naming the record's line and the first feature that moved. Each scene
/// carries its record's search tag and a replay tag {"of": records_path, "failed_only"}, so
/// the replay's records keep their law (failed_only: chosen by outcome).
harness::ReplaySourceFactory MakeRegeneratedSources(
    const lang::CompiledProgram& program, const sampling::SampleOptions& options,
    const std::vector<search::ReportRecord>& records, const std::string& records_path,
    bool failed_only);

}  // namespace prs::cli
