// Mesh files at compile time (spec §10): every `Mesh("file")` with a string literal is found,
// read and loaded once (shapes::LoadMeshShape), so scenes never touch the disk; bad files are
// located errors at the literal, doubtful ones (open, zero-area triangles, odd units) warnings.
#include <set>

#include "lang/program_files.h"

namespace prs::lang::internal {
namespace {

struct MeshLiteral {
  std::string name;
  SourceSpan span;
  double scale = 1;  // the literal scale when it is a number, for the units warning
};

class MeshCallCollector {
 public:
  explicit MeshCallCollector(std::vector<MeshLiteral>* out) : out_(out) {}

  void Body(const std::vector<StmtPtr>& body) {
    for (const StmtPtr& stmt : body) Statement(*stmt);
  }

  void Expression(const ExprPtr& e) {
    if (e) Visit(*e);
  }

 private:
  void Visit(const Expr& e) {
    if (const auto* call = std::get_if<CallExpr>(&e.node)) {
      const auto* callee = std::get_if<NameRef>(&call->callee->node);
      const auto* file = call->args.empty() ? nullptr : std::get_if<StringLit>(&call->args[0].value->node);
      if (callee && callee->name == "Mesh" && file) {
        MeshLiteral literal{file->value, call->args[0].value->span};
        if (call->args.size() > 1) {
          if (const auto* n = std::get_if<NumberLit>(&call->args[1].value->node)) literal.scale = n->value;
        }
        out_->push_back(std::move(literal));
      }
    }
    ForEachChild(e, [&](const Expr& child) { Visit(child); });
  }

  void Statement(const Stmt& stmt) {
    std::visit(
        [&](const auto& node) {
          using T = std::decay_t<decltype(node)>;
          if constexpr (std::is_same_v<T, ExprStmt>) {
            Expression(node.expr);
          } else if constexpr (std::is_same_v<T, AssignStmt> || std::is_same_v<T, AugAssignStmt>) {
            Expression(node.value);
          } else if constexpr (std::is_same_v<T, ClassDef>) {
            for (const PropertyDecl& p : node.properties) Expression(p.default_value);
          } else if constexpr (std::is_same_v<T, FunctionDef>) {
            for (const Param& p : node.params) Expression(p.default_value);
            Body(node.body);
          } else if constexpr (std::is_same_v<T, ReturnStmt>) {
            Expression(node.value);
          } else if constexpr (std::is_same_v<T, IfStmt>) {
            for (const auto& [condition, body] : node.branches) {
              Expression(condition);
              Body(body);
            }
            Body(node.else_body);
          } else if constexpr (std::is_same_v<T, ForStmt>) {
            Expression(node.iterable);
            Body(node.body);
          } else if constexpr (std::is_same_v<T, WhileStmt>) {
            Expression(node.condition);
            Body(node.body);
          } else if constexpr (std::is_same_v<T, RequireStmt>) {
            Expression(node.condition);
            Expression(node.probability);
          } else if constexpr (std::is_same_v<T, ParamStmt>) {
            for (const auto& [name, value] : node.params) Expression(value);
          }
        },
        stmt.node);
  }

  std::vector<MeshLiteral>* out_;
};

}  // namespace

void LoadMeshFiles(CompiledProgram& program, const CompileOptions& options,
                   DiagnosticEngine& diagnostics) {
  std::vector<MeshLiteral> literals;
  MeshCallCollector collector(&literals);
  for (const auto& module : program.modules) collector.Body(module->ast.body);
  std::set<std::pair<std::string, double>> warned;
  for (const MeshLiteral& literal : literals) {
    auto it = program.meshes.find(literal.name);
    if (it == program.meshes.end()) {
      std::optional<ProgramFile> file =
          ReadProgramFile(program, options, literal.name, literal.span, "mesh file", diagnostics);
      if (!file) continue;
      try {
        auto shape = shapes::LoadMeshShape(file->bytes, literal.name, file->path);
        it = program.meshes.emplace(literal.name,
                                    CompiledProgram::MeshFile{std::move(shape), file->path,
                                                              std::move(file->bytes)}).first;
      } catch (const shapes::MeshError& e) {
        Diagnostic d;
        d.id = "bad-mesh";
        d.span = literal.span;
        d.message = "the mesh file '" + literal.name + "' " + e.what();
        diagnostics.Report(std::move(d));
        continue;
      }
    }
    if (!(literal.scale > 0) || !warned.insert({literal.name, literal.scale}).second) continue;
    for (const std::string& warning : shapes::DescribeMeshWarnings(*it->second.shape, literal.scale)) {
      Diagnostic d;
      d.id = "mesh-warning";
      d.severity = Severity::kWarning;
      d.span = literal.span;
      d.message = "the mesh '" + literal.name + "' " + warning;
      diagnostics.Report(std::move(d));
    }
  }
}

}  // namespace prs::lang::internal
