// Upward-facing support surfaces of a mesh: see support.h.
#include "shapes/support.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include "shapes/mesh.h"

#include "shapes/qhull_session.h"

namespace prs::shapes {
namespace {

// Union-find over triangle indices.
int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

double CalcPlanarHullArea(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal) {
  if (points.size() < 3) return 0;
  // Coordinates in the plane: two unit vectors orthogonal to the normal.
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.normalized().cross(u);
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 2);
  for (const Eigen::Vector3d& p : points) coordinates.insert(coordinates.end(), {u.dot(p), v.dot(p)});
  double area = 0;
  // FA: compute the hull's area and volume (in 2-D, totvol is its area).
  internal::RunQhull(2, coordinates, "qhull FA", [&](qhT* qh) { area = qh->totvol; });
  return area;
}

std::vector<SupportPolygon> CalcSupportPolygons(const TriangleMesh& mesh, double max_tilt_rad) {
  const std::vector<Eigen::Vector3d>& p = mesh.vertices_O;
  const int n = static_cast<int>(mesh.triangles.size());
  std::vector<Eigen::Vector3d> normals(n);
  std::vector<double> areas(n);
  std::vector<bool> up(n, false);
  const double min_cos = std::cos(max_tilt_rad);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3i& t = mesh.triangles[i];
    const Eigen::Vector3d cross = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    areas[i] = cross.norm() / 2;
    if (!(areas[i] > 0)) continue;
    normals[i] = cross.normalized();
    up[i] = normals[i].z() >= min_cos;
  }
  // Upward triangles sharing an edge and a plane (every vertex of one within 1e-9 m of the
  // other's plane, normals within 1e-9) join one piece.
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::map<std::pair<int, int>, int> first_on_edge;
  for (int i = 0; i < n; ++i) {
    if (!up[i]) continue;
    const Eigen::Vector3i& t = mesh.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> edge{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])};
      auto [it, fresh] = first_on_edge.emplace(edge, i);
      if (fresh) continue;
      const int j = it->second;
      bool coplanar = (normals[i] - normals[j]).norm() < 1e-9;
      for (int m = 0; m < 3 && coplanar; ++m) {
        coplanar = std::abs(normals[j].dot(p[t[m]] - p[mesh.triangles[j][0]])) < 1e-9;
      }
      if (coplanar) parent[FindRoot(parent, i)] = FindRoot(parent, j);
    }
  }
  std::map<int, std::vector<int>> groups;
  for (int i = 0; i < n; ++i) {
    if (up[i]) groups[FindRoot(parent, i)].push_back(i);
  }
  std::vector<SupportPolygon> pieces;
  for (const auto& [root, members] : groups) {
    double area = 0;
    std::vector<int> ids;
    for (int i : members) {
      area += areas[i];
      for (int k = 0; k < 3; ++k) ids.push_back(mesh.triangles[i][k]);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<Eigen::Vector3d> vertices;
    for (int id : ids) vertices.push_back(p[id]);
    const Eigen::Vector3d normal = normals[root];
    // Convex when the triangles fill their hull (areas agree to 1e-9 relative).
    if (members.size() == 1 || std::abs(CalcPlanarHullArea(vertices, normal) - area) <= 1e-9 * area) {
      pieces.push_back({std::move(vertices), normal, area});
      continue;
    }
    for (int i : members) {
      const Eigen::Vector3i& t = mesh.triangles[i];
      pieces.push_back({{p[t[0]], p[t[1]], p[t[2]]}, normals[i], areas[i]});
    }
  }
  std::stable_sort(pieces.begin(), pieces.end(),
                   [](const SupportPolygon& a, const SupportPolygon& b) { return a.area > b.area; });
  return pieces;
}

}  // namespace prs::shapes
