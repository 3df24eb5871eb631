// Internal to the export library: the rules that turn one object (from a sampled scene or from
// a scenes file) into a Body, shared by MakeExportScene and ReadSceneJson.
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "export/export.h"

namespace prs::exporting::internal {

using Properties = std::vector<std::pair<std::string, lang::Value>>;

/// What the rules read about one object.
struct ObjectFacts {
  std::string name;  // the variable, or "" for an anonymous object
  std::string class_name;
  int index = 0;  // in the scene, for names of anonymous objects
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();
  Eigen::Quaterniond R_WO = Eigen::Quaterniond::Identity();
  Eigen::Vector3d dimensions = Eigen::Vector3d::Zero();
  bool allow_collisions = false;
  Properties properties;  // a copy: the scene's container type is not part of this contract
};

/// Makes unique identifier names; "world" and "ground" are reserved for the exporters.
class NameTable {
 public:
  NameTable() : taken_{"world", "ground"} {}
  /// `wanted` made an identifier ([A-Za-z_][A-Za-z0-9_]*), with "_2", "_3", ... if taken.
  std::string MakeUnique(const std::string& wanted);

 private:
  std::set<std::string> taken_;
};

/// Principal moments of inertia of a solid `shape` of `size` and `mass_kg` about its centre,
/// in its own axes (a mesh: its bounding box's).
Eigen::Vector3d CalcInertiaDiag(Shape shape, const Eigen::Vector3d& size, double mass_kg);

/// Applies the rules of docs/export.md; appends a sentence to `warnings` for each property it
/// cannot read.
Body MakeBody(const ObjectFacts& facts, NameTable& names, std::vector<std::string>& warnings);

}  // namespace prs::exporting::internal
