// Small meshes for the shapes tests, written as OBJ text: a box, a ring (a square "handle"
// with a hole) and helpers to turn vertex and triangle lists into file text.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace prs::shapes::testing {

inline std::string FormatObj(const std::vector<Eigen::Vector3d>& v,
                             const std::vector<Eigen::Vector3i>& t) {
  std::string text = "# test mesh\n";
  for (const Eigen::Vector3d& p : v) {
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  for (const Eigen::Vector3i& f : t) {
    text += "f " + std::to_string(f[0] + 1) + " " + std::to_string(f[1] + 1) + " " +
            std::to_string(f[2] + 1) + "\n";
  }
  return text;
}

/// A closed box [lo, hi] as 8 vertices and 12 outward-facing triangles.
inline void AppendBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                      std::vector<Eigen::Vector3d>& v, std::vector<Eigen::Vector3i>& t) {
  const int b = static_cast<int>(v.size());
  for (int k = 0; k < 8; ++k) {
    v.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    t.emplace_back(b + f[0], b + f[1], b + f[2]);
    t.emplace_back(b + f[0], b + f[2], b + f[3]);
  }
}

inline std::string BoxObj(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> t;
  AppendBox(lo, hi, v, t);
  return FormatObj(v, t);
}

/// A square ring in the xz plane: four bars of thickness `bar` around a hole, outer size
/// `outer` (x and z), `depth` along y, centred on the origin. Its bounding box is solid, the
/// ring is not: a small object fits in the hole without touching it.
inline std::string RingObj(double outer, double bar, double depth) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> t;
  const double o = outer / 2, i = o - bar, d = depth / 2;
  AppendBox({-o, -d, -o}, {o, d, -i}, v, t);  // bottom bar
  AppendBox({-o, -d, i}, {o, d, o}, v, t);    // top bar
  AppendBox({-o, -d, -i}, {-i, d, i}, v, t);  // left bar
  AppendBox({i, -d, -i}, {o, d, i}, v, t);    // right bar
  return FormatObj(v, t);
}

}  // namespace prs::shapes::testing
