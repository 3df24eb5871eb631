// Arms for `reachable by` (spec §10): the URDF files a program names are read when it is
// compiled (the language never touches the disk while it runs); kinematic chains and
// reachable sets are built on first use, shared by every thread that samples the program,
// and reachable sets are cached on disk (kinematics/reach.h).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "geometry/union.h"
#include "kinematics/chain.h"
#include "kinematics/reach.h"
#include "lang/diagnostics.h"
#include "lang/lang.h"

namespace prs::lang::internal {

/// The name of the built-in arm model, the value of an `arm` property ("panda").
inline constexpr const char* kBuiltinPanda = "panda";

/// A reachable set ready for placement: the cells as a PieceSet in the arm's base frame.
struct ArmReach {
  std::shared_ptr<const geometry::PieceSet> cells_Base;
  double volume_m3 = 0;
  std::string description;  // "panda, down grasp, margin 0 m, approach 0 m: 2,824 cells, 1.79 m³"
};

/// The program's arms: thread-safe; owned by the CompiledProgram.
class ArmStore {
 public:
  ArmStore(std::string cache_dir, double resolution_m,
           std::function<void(const std::string&)> on_note);

  /// Keeps a URDF file's text under the string the program names it by (its `arm` value).
  void AddUrdf(const std::string& name, std::string path, std::string text);
  /// The URDF files added, by name.
  std::vector<ProgramResource> ListUrdfs();

  /// The chain of arm model `name` ("panda", or a URDF file added under that name) from
  /// `base_link` to `tool_link` ("" = the file's root / only leaf). Throws
  /// kinematics::KinematicsError with a message for the user, also when `name` is neither.
  std::shared_ptr<const kinematics::Chain> GetChain(const std::string& name,
                                                    const std::string& base_link,
                                                    const std::string& tool_link);

  /// The reachable set of `chain` (one GetChain returned) for `options`, computed (or loaded
  /// from the disk cache) the first time it is asked for. Throws kinematics::KinematicsError
  /// for bad options.
  std::shared_ptr<const ArmReach> GetReach(const std::shared_ptr<const kinematics::Chain>& chain,
                                           kinematics::ReachOptions options);

 private:
  struct Urdf {
    std::string path, text;
  };
  std::string cache_dir_;
  double resolution_m_ = 0;  // 0: ReachOptions' default
  std::function<void(const std::string&)> on_note_;
  std::mutex mutex_;  // guards the maps; computing a set holds it (others wait for it anyway)
  std::map<std::string, Urdf> urdfs_;
  std::map<std::tuple<std::string, std::string, std::string>, std::shared_ptr<const kinematics::Chain>> chains_;
  // By chain (GetChain keeps each chain alive, so its address is its identity) and options.
  using ReachKey = std::tuple<const kinematics::Chain*, int, double, double, double, double>;
  std::map<ReachKey, std::shared_ptr<const ArmReach>> reaches_;
};

/// Reads every URDF file the program names as an `arm` property by a string literal (a class
/// default `arm: "ur5.urdf"` or a specifier `with arm "ur5.urdf"`), relative to the file that
/// names it, then the search path, and stores it in program.arms (which it creates). An
/// unreadable file is a located error.
void LoadArmFiles(CompiledProgram& program, const CompileOptions& options,
                  DiagnosticEngine& diagnostics);

}  // namespace prs::lang::internal
