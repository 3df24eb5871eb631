// The compiler driver: reads the main file, loads `from NAME import *` modules (searching the
// importing file's directory, then the search path; cycles are errors), parses everything, and
// hands the modules to the resolver, which builds the class table and creation plans.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "lang/arms.h"
#include "lang/program_files.h"
#include "lang/lang.h"
#include "lang/parser.h"
#include "lang/resolve.h"

namespace prs::lang {
namespace {

class DiskFileSystem final : public FileSystem {
 public:
  std::optional<std::string> ReadFile(const std::string& path) const override {
    // Any file but a directory: devices and pipes (`/dev/stdin`, `<(generate)`) read too.
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
};

// Loads modules depth-first as the parser meets their imports.
class ModuleLoader {
 public:
  ModuleLoader(CompiledProgram& program, const CompileOptions& options,
               DiagnosticEngine& diagnostics)
      : program_(program), options_(options), diagnostics_(diagnostics),
        fs_(options.file_system ? *options.file_system : RealFileSystem()) {}

  // Parses `text` as module `name` and every module it imports; returns its index.
  int LoadModule(const std::string& name, const std::string& path, std::string text) {
    // A UTF-8 byte-order mark (editors on Windows write one) is not part of the program.
    if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);
    const FileId file = program_.sources.AddFile(path, std::move(text));
    // Modules are known by their file's stem, so a module importing the main file by name
    // is a cycle too.
    loading_.push_back(std::filesystem::path(path).stem().string());
    ParseOptions parse_options;
    const std::string directory = std::filesystem::path(path).parent_path().string();
    parse_options.import_classes = [this, directory](const std::string& module,
                                                     SourceSpan where) {
      return ImportClasses(module, directory, where);
    };
    auto info = std::make_unique<ModuleInfo>();
    info->name = name;
    info->file = file;
    info->ast = Parse(file, program_.sources, diagnostics_, parse_options);
    loading_.pop_back();
    program_.modules.push_back(std::move(info));
    const int index = static_cast<int>(program_.modules.size()) - 1;
    loaded_[name] = index;
    return index;
  }

  const std::map<std::string, int>& loaded() const { return loaded_; }

 private:
  // The parser's hook: load `module` if needed and return the class names it exports.
  std::optional<std::vector<std::string>> ImportClasses(const std::string& module,
                                                        const std::string& directory,
                                                        SourceSpan where) {
    for (const std::string& open : loading_) {
      if (open == module) {
        ReportCycle(module, where);
        return std::nullopt;
      }
    }
    auto it = loaded_.find(module);
    int index = -1;
    if (it != loaded_.end()) {
      index = it->second;
    } else {
      std::optional<std::string> path = FindModule(module, directory);
      if (!path) {
        ReportMissing(module, directory, where);
        return std::nullopt;
      }
      index = LoadModule(module, *path, *fs_.ReadFile(*path));
    }
    std::vector<std::string> names;
    std::vector<bool> visited(program_.modules.size(), false);
    CollectExportedClassNames(index, visited, names);
    return names;
  }

  // Class names a module makes visible: its own classes and those of the modules it imports.
  // `visited` guards against import cycles, which are reported but still leave a loop here.
  void CollectExportedClassNames(int index, std::vector<bool>& visited,
                                 std::vector<std::string>& names) const {
    if (visited[index]) return;
    visited[index] = true;
    for (const StmtPtr& stmt : program_.modules[index]->ast.body) {
      if (const auto* cls = std::get_if<ClassDef>(&stmt->node)) {
        names.push_back(cls->name.name);
      } else if (const auto* import = std::get_if<FromImportStmt>(&stmt->node)) {
        auto it = loaded_.find(import->module.name);
        if (it != loaded_.end()) CollectExportedClassNames(it->second, visited, names);
      }
    }
  }

  std::optional<std::string> FindModule(const std::string& module, const std::string& directory) {
    std::vector<std::string> directories{directory.empty() ? "." : directory};
    directories.insert(directories.end(), options_.search_path.begin(), options_.search_path.end());
    for (const std::string& dir : directories) {
      const std::string candidate = (std::filesystem::path(dir) / (module + ".prs")).string();
      if (fs_.ReadFile(candidate)) return candidate;
    }
    return std::nullopt;
  }

  void ReportCycle(const std::string& module, SourceSpan where) {
    std::string chain;
    for (const std::string& open : loading_) chain += open + " -> ";
    chain += module;
    Diagnostic d;
    d.id = "import-cycle";
    d.span = where;
    d.message = "import cycle: " + chain;
    d.notes.push_back({{}, false, "a module cannot import itself, directly or through others; "
                                  "move the shared definitions into a third module"});
    diagnostics_.Report(std::move(d));
  }

  void ReportMissing(const std::string& module, const std::string& directory, SourceSpan where) {
    std::string searched = directory.empty() ? "." : directory;
    for (const std::string& dir : options_.search_path) searched += ", " + dir;
    Diagnostic d;
    d.id = "module-not-found";
    d.span = where;
    d.message = "cannot find module '" + module + "' (looked for " + module + ".prs in " +
                searched + ")";
    d.notes.push_back({{}, false, "put " + module + ".prs next to this file, or add its "
                                  "directory with -I DIR or the PRS_PATH environment variable"});
    diagnostics_.Report(std::move(d));
  }

  CompiledProgram& program_;
  const CompileOptions& options_;
  DiagnosticEngine& diagnostics_;
  const FileSystem& fs_;
  std::vector<std::string> loading_;
  std::map<std::string, int> loaded_;
};

// Adds the names declared by `param` statements anywhere in `body` (blocks and functions too).
void CollectParamNames(const std::vector<StmtPtr>& body, std::vector<std::string>& names) {
  for (const StmtPtr& stmt : body) {
    if (const auto* param = std::get_if<ParamStmt>(&stmt->node)) {
      for (const auto& [name, value] : param->params) names.push_back(name.name);
    } else if (const auto* node = std::get_if<IfStmt>(&stmt->node)) {
      for (const auto& [condition, branch] : node->branches) CollectParamNames(branch, names);
      CollectParamNames(node->else_body, names);
    } else if (const auto* loop = std::get_if<ForStmt>(&stmt->node)) {
      CollectParamNames(loop->body, names);
    } else if (const auto* loop = std::get_if<WhileStmt>(&stmt->node)) {
      CollectParamNames(loop->body, names);
    } else if (const auto* function = std::get_if<FunctionDef>(&stmt->node)) {
      CollectParamNames(function->body, names);
    }
  }
}

// A `-p NAME=VALUE` for a NAME no `param` declares is almost always a typo: say so.
void CheckParamOverrides(const CompiledProgram& program, const CompileOptions& options,
                         DiagnosticEngine& diagnostics) {
  std::vector<std::string> declared;
  for (const auto& module : program.modules) CollectParamNames(module->ast.body, declared);
  for (const auto& [name, value] : options.param_overrides) {
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    if (!value.empty() && *end == '\0' && !std::isfinite(number)) {
      Diagnostic d;
      d.id = "bad-value";
      d.has_span = false;
      d.message = "-p " + name + "=" + value +
                  ": a param must be a finite number or a string (scene JSON cannot hold "
                  "infinity or NaN)";
      diagnostics.Report(std::move(d));
      continue;
    }
    if (std::find(declared.begin(), declared.end(), name) != declared.end()) continue;
    Diagnostic d;
    d.id = "unknown-param";
    d.has_span = false;
    d.message = "-p " + name + "=" + value + ": the program declares no param '" + name + "'";
    const std::string suggestion = SuggestClosest(name, declared);
    if (!suggestion.empty()) d.message += "; did you mean '" + suggestion + "'?";
    diagnostics.Report(std::move(d));
  }
}

// Why the real file system could not read `path`, for the message.
std::string DescribeUnreadable(const std::string& path, const FileSystem* injected) {
  std::error_code error;
  if (injected) return "no such file, or it is not readable";
  if (!std::filesystem::exists(path, error)) return "no such file";
  if (std::filesystem::is_directory(path, error)) return "it is a directory; give a .prs file";
  return "permission denied, or it is not readable";
}

}  // namespace

std::string DefaultCacheDir() {
  if (const char* dir = std::getenv("PRS_CACHE_DIR")) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    return (std::filesystem::path(xdg) / "probrobscene").string();
  }
  if (const char* home = std::getenv("HOME"); home && *home) {
    return (std::filesystem::path(home) / ".cache" / "probrobscene").string();
  }
  return "";
}

const FileSystem& RealFileSystem() {
  static const DiskFileSystem kDisk;
  return kDisk;
}

std::unique_ptr<CompiledProgram> CompileText(const std::string& path, std::string text,
                                             const CompileOptions& options,
                                             DiagnosticEngine& diagnostics) {
  auto program = std::make_unique<CompiledProgram>();
  ModuleLoader loader(*program, options, diagnostics);
  program->main_module = loader.LoadModule(path, path, std::move(text));
  for (const auto& [name, value] : options.param_overrides) program->param_overrides[name] = value;
  if (!diagnostics.has_errors()) ResolveProgram(*program, loader.loaded(), diagnostics);
  if (!diagnostics.has_errors()) CheckParamOverrides(*program, options, diagnostics);
  if (!diagnostics.has_errors()) internal::LoadArmFiles(*program, options, diagnostics);
  if (!diagnostics.has_errors()) internal::LoadMeshFiles(*program, options, diagnostics);
  return program;
}

std::unique_ptr<CompiledProgram> CompileFile(const std::string& path, const CompileOptions& options,
                                             DiagnosticEngine& diagnostics) {
  const FileSystem& fs = options.file_system ? *options.file_system : RealFileSystem();
  std::optional<std::string> text = fs.ReadFile(path);
  if (!text) {
    Diagnostic d;
    d.id = "file-not-found";
    d.has_span = false;
    d.message = "cannot read '" + path + "': " + DescribeUnreadable(path, options.file_system);
    diagnostics.Report(std::move(d));
    return std::make_unique<CompiledProgram>();
  }
  return CompileText(path, std::move(*text), options, diagnostics);
}

}  // namespace prs::lang
