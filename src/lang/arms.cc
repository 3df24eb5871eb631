// The program's arms: URDF files read at compile time, chains and reachable sets built once on
// first use (see arms.h).
#include "lang/arms.h"

#include <cstdio>

#include "kinematics/panda.h"
#include "kinematics/urdf.h"
#include "lang/program_files.h"

namespace prs::lang::internal {
namespace {

std::string FormatCount(size_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string DescribeOptions(const kinematics::ReachOptions& o) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%s grasp, margin %g m, approach %g m",
                kinematics::GraspName(o.grasp), o.margin_m, o.approach_m);
  return buffer;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A string literal given to the property `arm` (class default or `with arm`), with the file
// that names it.
struct ArmLiteral {
  std::string value;
  SourceSpan span;
};

void CollectArmLiterals(const CompiledProgram& program, std::vector<ArmLiteral>* out) {
  for (const auto& cls : program.classes) {
    for (const PropertyDefault& d : cls->defaults) {
      if (d.name != "arm" || !d.expr) continue;
      if (const auto* s = std::get_if<StringLit>(&d.expr->node)) out->push_back({s->value, d.expr->span});
    }
  }
  for (const auto& [create, plan] : program.plans) {
    for (const Specifier& spec : create->specifiers) {
      if (spec.kind != SpecifierKind::kWith || !spec.property || spec.property->name != "arm") continue;
      if (const auto* s = std::get_if<StringLit>(&spec.target->node)) out->push_back({s->value, spec.target->span});
    }
  }
}

}  // namespace

ArmStore::ArmStore(std::string cache_dir, double resolution_m,
                   std::function<void(const std::string&)> on_note)
    : cache_dir_(std::move(cache_dir)), resolution_m_(resolution_m), on_note_(std::move(on_note)) {}

void ArmStore::AddUrdf(const std::string& name, std::string path, std::string text) {
  std::lock_guard<std::mutex> lock(mutex_);
  urdfs_.emplace(name, Urdf{std::move(path), std::move(text)});
}

std::vector<ProgramResource> ArmStore::ListUrdfs() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<ProgramResource> out;
  for (const auto& [name, urdf] : urdfs_) out.push_back({name, urdf.path, urdf.text});
  return out;
}

std::shared_ptr<const kinematics::Chain> ArmStore::GetChain(const std::string& name,
                                                            const std::string& base_link,
                                                            const std::string& tool_link) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto key = std::make_tuple(name, base_link, tool_link);
  if (auto it = chains_.find(key); it != chains_.end()) return it->second;
  std::shared_ptr<const kinematics::Chain> chain;
  if (name == kBuiltinPanda) {
    if (!base_link.empty() || !tool_link.empty()) {
      throw kinematics::KinematicsError(
          "the built-in panda arm has fixed base and tool frames; 'arm_base' and 'arm_tool' "
          "are for URDF arms");
    }
    chain = std::make_shared<const kinematics::Chain>(kinematics::MakePandaChain());
  } else if (auto it = urdfs_.find(name); it != urdfs_.end()) {
    chain = std::make_shared<const kinematics::Chain>(
        kinematics::LoadUrdfChain(it->second.text, it->second.path, base_link, tool_link));
  } else if (EndsWith(name, ".urdf")) {
    throw kinematics::KinematicsError(
        "the URDF file '" + name + "' was not read when the program was compiled: name it with "
        "a string literal, as a class default `arm: \"" + name + "\"` or `with arm \"" + name +
        "\"`, so that it is loaded with the program");
  } else {
    throw kinematics::KinematicsError("'" + name + "' is not an arm model: an arm's 'arm' "
                                      "property is \"panda\" (the built-in Franka Panda) or the "
                                      "path of a .urdf file");
  }
  chains_.emplace(key, chain);
  return chain;
}

std::shared_ptr<const ArmReach> ArmStore::GetReach(
    const std::shared_ptr<const kinematics::Chain>& chain_ptr, kinematics::ReachOptions options) {
  const kinematics::Chain& chain = *chain_ptr;
  if (resolution_m_ > 0) options.resolution_m = resolution_m_;
  const ReachKey key{chain_ptr.get(), static_cast<int>(options.grasp), options.margin_m,
                     options.approach_m, options.resolution_m, options.max_sector_rad};
  std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = reaches_.find(key); it != reaches_.end()) return it->second;
  const kinematics::ReachLoad load = kinematics::LoadOrComputeReachableSet(chain, options, cache_dir_);
  auto reach = std::make_shared<ArmReach>();
  reach->cells_Base = std::make_shared<const geometry::PieceSet>(load.set->cells_Base);
  reach->volume_m3 = load.set->volume_m3;
  char volume[32];
  std::snprintf(volume, sizeof volume, "%.3g", load.set->volume_m3);
  reach->description = chain.name + ", " + DescribeOptions(options) + ": " +
                       FormatCount(load.set->cells_Base.size()) + " cells, " + volume + " m³";
  // Say so when it took time (a cache read is quick and not worth a line on every run).
  if (on_note_ && !load.from_cache) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f s", load.seconds);
    std::string note = "computed the reachable set of " + reach->description + " in " + seconds;
    if (!cache_dir_.empty()) note += "; cached in " + cache_dir_;
    on_note_(note);
  }
  if (on_note_ && !load.warning.empty()) on_note_("warning: " + load.warning);
  reaches_.emplace(key, reach);
  return reach;
}

void LoadArmFiles(CompiledProgram& program, const CompileOptions& options,
                  DiagnosticEngine& diagnostics) {
  program.arms = std::make_shared<ArmStore>(options.cache_dir, options.reach_resolution_m,
                                            options.on_note);
  std::vector<ArmLiteral> literals;
  CollectArmLiterals(program, &literals);
  std::map<std::string, bool> done;
  for (const ArmLiteral& literal : literals) {
    if (!EndsWith(literal.value, ".urdf") || done[literal.value]) continue;
    done[literal.value] = true;
    std::optional<ProgramFile> file =
        ReadProgramFile(program, options, literal.value, literal.span, "URDF file", diagnostics);
    if (file) program.arms->AddUrdf(literal.value, file->path, std::move(file->bytes));
  }
}

}  // namespace prs::lang::internal

namespace prs::lang {

std::vector<ProgramResource> ListResources(const CompiledProgram& program) {
  std::vector<ProgramResource> resources =
      program.arms ? program.arms->ListUrdfs() : std::vector<ProgramResource>{};
  for (const auto& [name, mesh] : program.meshes) resources.push_back({name, mesh.path, mesh.bytes});
  return resources;
}

}  // namespace prs::lang
