// Where `prs export` writes: choosing the format (--format, or -o's extension) and the target
// (one file, a directory of one file per scene, or stdout), with a usage message for each
// combination that cannot work.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "export/export.h"

namespace prs::cli {

/// Accepts a format name; otherwise "unknown format 'X'; did you mean 'Y'? (formats: ...)".
CLI::Validator FormatNameValidator();

/// The format named by --format (already validated), else the one -o's extension implies.
/// Prints a usage error and returns nullopt when neither names one.
std::optional<exporting::Format> ChooseFormat(const std::string& format_name,
                                              const std::string& output);

/// One file, stdout, or a directory with `STEM_sSEED_iINDEX.ext` per scene.
class ExportTarget {
 public:
  static ExportTarget Stdout();
  static ExportTarget File(std::filesystem::path path);
  static ExportTarget Directory(std::filesystem::path dir, std::string stem, std::string extension);

  bool to_stdout() const { return kind_ == Kind::kStdout; }
  /// Writes one scene's file (creating the directory first). Throws std::runtime_error with
  /// the path and the system's reason when it cannot.
  void Write(uint64_t seed, uint64_t index, const std::string& content) const;
  /// "scene.xml", or "out/ (table_cube_s1_i0.xml ...)".
  std::string Describe() const;

 private:
  enum class Kind { kStdout, kFile, kDirectory };
  ExportTarget(Kind kind, std::filesystem::path path, std::string stem, std::string extension)
      : kind_(kind),
        path_(std::move(path)),
        stem_(std::move(stem)),
        extension_(std::move(extension)) {}
  std::filesystem::path FileFor(uint64_t seed, uint64_t index) const;

  Kind kind_;
  std::filesystem::path path_;
  std::string stem_, extension_;
  mutable std::optional<std::string> first_file_;
};

/// Decides the target for `count` scenes in `format` from -o (`output`). Prints a usage error
/// and returns nullopt for: several scenes to one file or to stdout, an extension of another
/// format, binary glTF to a terminal, or an existing path that is not a directory.
std::optional<ExportTarget> PlanExportTarget(const std::string& output, exporting::Format format,
                                             int64_t count, const std::string& stem);

}  // namespace prs::cli
