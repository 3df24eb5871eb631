// Files a program names besides its modules (URDF arms, mesh shapes): found next to the file
// that names them, then along the search path (-I), and read once at compile time. Shared by
// arms.cc and meshes.cc so both say the same thing when a file is missing.
#pragma once

#include <optional>
#include <string>

#include "lang/diagnostics.h"
#include "lang/lang.h"
#include "lang/program.h"

namespace prs::lang::internal {

struct ProgramFile {
  std::string path;  // where it was read
  std::string bytes;
};

/// Reads the file `named` (a string literal at `span`; `kind` is e.g. "URDF file" or "mesh
/// file"). On failure reports a located "file-not-found" error (where it looked, what to do)
/// and returns nullopt.
std::optional<ProgramFile> ReadProgramFile(const CompiledProgram& program,
                                           const CompileOptions& options, const std::string& named,
                                           SourceSpan span, const char* kind,
                                           DiagnosticEngine& diagnostics);

/// The meshes `Mesh("file")` names with a string literal anywhere in the program, loaded and
/// checked (errors and warnings located at the literal), into program.meshes.
void LoadMeshFiles(CompiledProgram& program, const CompileOptions& options,
                   DiagnosticEngine& diagnostics);

}  // namespace prs::lang::internal
