// A static outline of a compiled scenario for `prs check` and Python's Scenario.check(): every
// object-creation site (class, variable, line, position specifiers and the kind of region they
// define) and the classes the program defines. Read from the AST and plans; nothing is run.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang/lang.h"

namespace prs::analysis {

/// Identifies a creation site, and the scene objects it made: (file, byte offset where the
/// creation expression starts), the same as SceneObject::span's file and begin.
using SiteKey = std::pair<lang::FileId, uint32_t>;

struct CreationSite {
  SiteKey key;
  std::string class_name;
  std::optional<std::string> variable;           // `NAME = Class ...`; none for anonymous objects
  std::vector<std::string> position_specifiers;  // as spelled: "completely on", "left of"
  std::string position_region;                   // see DescribePositionRegion
};

struct ClassOutline {
  std::string name;
  std::string parent;  // "Object" for classes declared without one
  lang::SourceSpan span;
  std::vector<std::string> own_properties;  // defaults this class adds or overrides
};

struct ScenarioOutline {
  std::vector<CreationSite> sites;    // in source order, main file first
  std::vector<ClassOutline> classes;  // user classes, in definition order
};

ScenarioOutline OutlineScenario(const lang::CompiledProgram& program);

/// The kind of region an object's position specifiers define, decided from their syntax:
/// "point" (`at`, `beyond`, `on` a vector expression), else "region (A ∩ B ...)" built from
/// "plane" (`on`/`completely on` a surface, `aligned with`), "half-spaces" (`left of`, ...,
/// and the edges of an `on` surface), the text of an `in` region, and "workspace" when the
/// workspace is folded in; "class default" with no position specifier.
std::string DescribePositionRegion(const lang::ObjectPlan& plan,
                                   const lang::SourceManager& sources);

}  // namespace prs::analysis
