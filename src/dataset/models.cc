// BOP's models/ folder: each labelled class's shape as a PLY file in millimetres (in the
// object's own frame, the one cam_R_m2c and cam_t_m2c place), and models_info.json with its
// extent, diameter and symmetries.
#include "dataset/models.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace prs::dataset {
namespace {

// Binary little-endian PLY with normals and triangle faces, as the BOP toolkit's load_ply
// reads it.
std::string FormatPly(const exporting::TriangleMesh& mesh) {
  const uint32_t vertices = mesh.vertex_count(), faces = uint32_t(mesh.indices.size() / 3);
  std::string out = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment prs dataset model, millimetres\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      vertices, faces);
  const auto append = [&out](const void* data, size_t bytes) {
    out.append(static_cast<const char*>(data), bytes);
  };
  static_assert(std::endian::native == std::endian::little, "PLY bytes are written as is");
  for (uint32_t v = 0; v < vertices; ++v) {
    for (int k = 0; k < 3; ++k) {
      const float mm = 1000.0f * mesh.positions[3 * v + k];
      append(&mm, 4);
    }
    append(&mesh.normals[3 * v], 12);
  }
  for (uint32_t f = 0; f < faces; ++f) {
    const uint8_t three = 3;
    append(&three, 1);
    for (int k = 0; k < 3; ++k) {
      const int32_t index = int32_t(mesh.indices[3 * f + k]);
      append(&index, 4);
    }
  }
  return out;
}

// The rotations other than the identity that map a box of these sizes onto itself: the
// signed permutations of determinant 1 that only exchange axes of equal size.
std::vector<Eigen::Matrix3d> ListBoxSymmetries(const Eigen::Vector3d& size) {
  std::vector<Eigen::Matrix3d> rotations;
  const int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const double tolerance = 1e-9 * size.maxCoeff();
  for (const auto& p : permutations) {
    bool same = true;
    for (int i = 0; i < 3; ++i) same = same && std::abs(size[p[i]] - size[i]) <= tolerance;
    if (!same) continue;
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 3; ++i) R(i, p[i]) = (signs >> i) & 1 ? -1 : 1;
      if (R.determinant() < 0 || R.isIdentity()) continue;
      rotations.push_back(R);
    }
  }
  return rotations;
}

nlohmann::json FormatTransform(const Eigen::Matrix3d& R) {
  nlohmann::json m = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m.push_back(R(i, j));
    m.push_back(0.0);  // translation, millimetres: the shapes are centred on their origin
  }
  for (const double x : {0.0, 0.0, 0.0, 1.0}) m.push_back(x);
  return m;
}

}  // namespace

ModelFile MakeModelFile(const exporting::Body& body) {
  const exporting::TriangleMesh mesh = exporting::MakeBodyTriangles(body);
  ModelFile model;
  model.ply = FormatPly(mesh);
  const uint32_t n = mesh.vertex_count();
  Eigen::Vector3d low = Eigen::Vector3d::Constant(HUGE_VAL), high = -low;
  std::vector<Eigen::Vector3d> points_mm;
  for (uint32_t v = 0; v < n; ++v) {
    const Eigen::Vector3d p(mesh.positions[3 * v], mesh.positions[3 * v + 1],
                            mesh.positions[3 * v + 2]);
    points_mm.push_back(1000.0 * p);
    low = low.cwiseMin(points_mm.back());
    high = high.cwiseMax(points_mm.back());
  }
  // The diameter: the largest distance between two vertices (faces share vertices, so the
  // distinct ones are few even for a mesh of many triangles).
  std::sort(points_mm.begin(), points_mm.end(), [](const auto& a, const auto& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  points_mm.erase(std::unique(points_mm.begin(), points_mm.end()), points_mm.end());
  double diameter = 0;
  for (size_t i = 0; i < points_mm.size(); ++i) {
    for (size_t j = i + 1; j < points_mm.size(); ++j) {
      diameter = std::max(diameter, (points_mm[i] - points_mm[j]).norm());
    }
  }
  nlohmann::json& info = model.info;
  info["diameter"] = diameter;
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    info[std::string("min_") + axes[k]] = n ? low[k] : 0.0;
    info[std::string("size_") + axes[k]] = n ? high[k] - low[k] : 0.0;
  }
  if (body.shape == exporting::Shape::kBox) {
    nlohmann::json discrete = nlohmann::json::array();
    for (const Eigen::Matrix3d& R : ListBoxSymmetries(body.size)) {
      discrete.push_back(FormatTransform(R));
    }
    if (!discrete.empty()) info["symmetries_discrete"] = discrete;
  } else if (body.shape == exporting::Shape::kCylinder) {
    // Any turn about its axis, and the half turn that swaps its ends.
    info["symmetries_continuous"] = {{{"axis", {0, 0, 1}}, {"offset", {0, 0, 0}}}};
    info["symmetries_discrete"] = {FormatTransform(Eigen::Vector3d(1, -1, -1).asDiagonal())};
  }
  return model;
}

}  // namespace prs::dataset
