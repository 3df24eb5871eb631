// Formats the sections of the `prs check` summary as aligned tables.
#include "cli/check_report.h"

#include <fmt/format.h>

#include "cli/common.h"
#include "cli/text_table.h"

namespace prs::cli {
namespace {

std::string FormatWhere(lang::FileId file, uint32_t offset, const lang::SourceManager& sources) {
  if (file >= sources.file_count()) return "-";
  return fmt::format("{}:{}", sources.path(file), sources.CalcLineColumn(file, offset).line);
}

std::string Join(const std::vector<std::string>& items, const char* separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

// "position, yaw", "count 1-3 per scene, position", "fixed", or "not created".
std::string DescribeVariation(const SiteVariation* variation, int64_t scenes) {
  if (!variation) return "not created in these scenes";
  std::vector<std::string> parts;
  const int64_t min_objects = variation->scenes_present < scenes ? 0 : variation->min_objects;
  if (min_objects != variation->max_objects) {
    parts.push_back(fmt::format("count {}-{} per scene", min_objects, variation->max_objects));
  }
  parts.insert(parts.end(), variation->varied.begin(), variation->varied.end());
  return parts.empty() ? "fixed" : Join(parts, ", ");
}

}  // namespace

std::string FormatCheckHeader(const std::string& file, const std::string& verdict,
                              const lang::CompiledProgram& program,
                              const ScenarioOutline& outline) {
  return fmt::format("{}: {} ({}, {}, {})\n", file, verdict,
                     FormatCount(int64_t(program.modules.size()), "module"),
                     FormatCount(int64_t(outline.classes.size()), "class"),
                     FormatCount(int64_t(outline.sites.size()), "creation site"));
}

std::string FormatObjectsSection(const ScenarioOutline& outline,
                                 const lang::SourceManager& sources) {
  if (outline.sites.empty()) return "\nobjects: none created\n";
  TextTable table({"where", "name", "class", "position specifiers", "position region"});
  for (const CreationSite& site : outline.sites) {
    table.AddRow({FormatWhere(site.key.first, site.key.second, sources),
                  site.variable.value_or("-"), site.class_name,
                  site.position_specifiers.empty() ? "-" : Join(site.position_specifiers, ", "),
                  site.position_region});
  }
  return "\nobjects (creation sites, in source order; region kind from the specifiers)\n" +
         table.Format();
}

std::string FormatRandomSection(const ScenarioOutline& outline, const VariationObserver& observed,
                                uint64_t seed, const lang::SourceManager& sources) {
  if (outline.sites.empty()) return "";
  TextTable table({"where", "name", "class", "varied between scenes"});
  for (const CreationSite& site : outline.sites) {
    const auto found = observed.sites().find(site.key);
    const SiteVariation* variation = found == observed.sites().end() ? nullptr : &found->second;
    table.AddRow({FormatWhere(site.key.first, site.key.second, sources),
                  site.variable.value_or("-"), site.class_name,
                  DescribeVariation(variation, observed.scenes())});
  }
  return fmt::format("\nrandom properties, observed over {} (seed {}, indices 0-{})\n",
                     FormatCount(observed.scenes(), "scene"), seed, observed.scenes() - 1) +
         table.Format();
}

std::string FormatClassesSection(const ScenarioOutline& outline,
                                 const lang::SourceManager& sources) {
  if (outline.classes.empty()) return "\nclasses: none defined\n";
  TextTable table({"class", "parent", "defined at", "own properties"});
  for (const ClassOutline& cls : outline.classes) {
    table.AddRow({cls.name, cls.parent.empty() ? "-" : cls.parent,
                  FormatWhere(cls.span.file, cls.span.begin, sources),
                  cls.own_properties.empty() ? "-" : Join(cls.own_properties, ", ")});
  }
  return "\nclasses\n" + table.Format();
}

}  // namespace prs::cli
