// Internal to src/dataset: a labelled class's model file and its models_info.json entry.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "export/export.h"

namespace prs::dataset {

struct ModelFile {
  std::string ply;      // binary little-endian PLY, millimetres, the object's own frame
  nlohmann::json info;  // diameter, min_/size_ per axis (mm), symmetries_* where it has them
};

/// The body's shape (exporting::MakeBodyTriangles) as BOP's model: a box's discrete
/// symmetries (the half turns about each axis, and the quarter turns about an axis whose two
/// other sizes are equal), a cylinder's turn about its axis and the half turn that swaps its
/// ends; no symmetry is claimed for other shapes.
ModelFile MakeModelFile(const exporting::Body& body);

}  // namespace prs::dataset
