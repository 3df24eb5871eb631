// Finding and reading the files a program names: see program_files.h.
#include "lang/program_files.h"

#include <filesystem>
#include <vector>

namespace prs::lang::internal {

std::optional<ProgramFile> ReadProgramFile(const CompiledProgram& program,
                                           const CompileOptions& options, const std::string& named,
                                           SourceSpan span, const char* kind,
                                           DiagnosticEngine& diagnostics) {
  const FileSystem& fs = options.file_system ? *options.file_system : RealFileSystem();
  const std::filesystem::path name(named);
  std::vector<std::string> directories{
      std::filesystem::path(program.sources.path(span.file)).parent_path().string()};
  directories.insert(directories.end(), options.search_path.begin(), options.search_path.end());
  std::string searched;
  for (const std::string& dir : directories) {
    const std::string path = name.is_absolute()
        ? name.string()
        : (std::filesystem::path(dir.empty() ? "." : dir) / name).string();
    if (std::optional<std::string> bytes = fs.ReadFile(path)) return ProgramFile{path, std::move(*bytes)};
    searched += (searched.empty() ? "" : ", ") + (dir.empty() ? std::string(".") : dir);
    if (name.is_absolute()) break;
  }
  Diagnostic d;
  d.id = "file-not-found";
  d.span = span;
  d.message = std::string("cannot read the ") + kind + " '" + named + "'" +
              (name.is_absolute() ? "" : " (looked in " + searched + ")");
  d.notes.push_back({{}, false, "give a path relative to this .prs file, or add its "
                                "directory with -I DIR"});
  diagnostics.Report(std::move(d));
  return std::nullopt;
}

}  // namespace prs::lang::internal
