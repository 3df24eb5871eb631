// `prs export`'s choice of format and output target, and the files it writes.
#include "cli/export_output.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>

#include "cli/common.h"

namespace prs::cli {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> FormatNames() {
  std::vector<std::string> names;
  std::string list = exporting::ListFormatNames();
  for (size_t at = 0; at != std::string::npos;) {
    const size_t comma = list.find(", ", at);
    names.push_back(list.substr(at, comma == std::string::npos ? comma : comma - at));
    at = comma == std::string::npos ? comma : comma + 2;
  }
  return names;
}

void WriteFile(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << content;
  out.close();
  if (!out) {
    throw std::runtime_error(
        fmt::format("cannot write {}: {}", path.string(), std::strerror(errno)));
  }
}

}  // namespace

CLI::Validator FormatNameValidator() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (exporting::ParseFormat(text)) return "";
        const std::string suggestion = lang::SuggestClosest(text, FormatNames());
        return fmt::format("unknown format '{}'{} (formats: {})", text,
                           suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?",
                           exporting::ListFormatNames());
      },
      "");
}

std::optional<exporting::Format> ChooseFormat(const std::string& format_name,
                                              const std::string& output) {
  if (!format_name.empty()) return exporting::ParseFormat(format_name);
  if (auto format = exporting::FormatFromExtension(fs::path(output).extension().string()))
    return format;
  PrintError(
      fmt::format("no format: give --format ({}) or -o with a file extension "
                  "(.xml, .urdf, .sdf, .usda, .gltf, .glb)",
                  exporting::ListFormatNames()));
  return std::nullopt;
}

ExportTarget ExportTarget::Stdout() { return ExportTarget(Kind::kStdout, {}, {}, {}); }
ExportTarget ExportTarget::File(fs::path path) {
  return ExportTarget(Kind::kFile, std::move(path), {}, {});
}
ExportTarget ExportTarget::Directory(fs::path dir, std::string stem, std::string extension) {
  // "worlds/" and "worlds" name one directory; keep messages free of "worlds//".
  while (!dir.has_filename() && dir.has_parent_path() && dir != dir.root_path()) {
    dir = dir.parent_path();
  }
  return ExportTarget(Kind::kDirectory, std::move(dir), std::move(stem), std::move(extension));
}

fs::path ExportTarget::FileFor(uint64_t seed, uint64_t index) const {
  return path_ / fmt::format("{}_s{}_i{}{}", stem_, seed, index, extension_);
}

void ExportTarget::Write(uint64_t seed, uint64_t index, const std::string& content) const {
  switch (kind_) {
    case Kind::kStdout:
      std::cout << content << std::flush;
      if (!std::cout) throw std::runtime_error("cannot write to stdout");
      return;
    case Kind::kFile:
      return WriteFile(path_, content);
    case Kind::kDirectory: {
      std::error_code error;
      fs::create_directories(path_, error);
      if (error) {
        throw std::runtime_error(
            fmt::format("cannot create directory {}: {}", path_.string(), error.message()));
      }
      const fs::path file = FileFor(seed, index);
      if (!first_file_) first_file_ = file.filename().string();
      return WriteFile(file, content);
    }
  }
}

std::string ExportTarget::Describe() const {
  if (kind_ == Kind::kStdout) return "stdout";
  if (kind_ == Kind::kFile) return path_.string();
  return fmt::format("{}/ ({} ...)", path_.string(), first_file_.value_or("no files"));
}

std::optional<ExportTarget> PlanExportTarget(const std::string& output, exporting::Format format,
                                             int64_t count, const std::string& stem) {
  const std::string extension = fs::path(output).extension().string();
  const auto implied = exporting::FormatFromExtension(extension);
  std::string problem;
  if (output.empty() || output == "-") {
    if (count > 1)
      problem = fmt::format("{} scenes make {} files: give a directory with -o DIR", count, count);
    else if (format == exporting::Format::kGlb && IsStdoutTerminal())
      problem = "glb is binary: give -o FILE.glb or redirect stdout";
    if (problem.empty()) return ExportTarget::Stdout();
  } else if (implied && *implied != format) {
    problem = fmt::format("-o {} has the extension of {}, but the format is {}", output,
                          exporting::FormatName(*implied), exporting::FormatName(format));
  } else if (implied) {
    if (count > 1)
      problem = fmt::format(
          "-o {} names one file, but {} scenes were asked for; "
          "give a directory with -o DIR",
          output, count);
    if (problem.empty()) return ExportTarget::File(output);
  } else if (fs::exists(output) && !fs::is_directory(output)) {
    problem = fmt::format("-o {} exists and is not a directory", output);
  } else {
    return ExportTarget::Directory(output, stem, exporting::FileExtension(format));
  }
  PrintError(problem);
  std::cerr << "run 'prs export --help' for usage\n";
  return std::nullopt;
}

}  // namespace prs::cli
