// Convex pieces of a mesh (decompose.h): connected parts, an exact convexity test, and HACD
// for the parts that are not convex. HACD is the library made for this job in Debian
// (libbullet-extras-dev); V-HACD and CoACD are not packaged there.
#include "shapes/decompose.h"

#include <HACD/hacdHACD.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <map>
#include <mutex>
#include <numeric>
#include <string>

namespace prs::shapes {
namespace {

// HACD's concavity limit, in its normalised units (the part scaled to 1,000 across its
// bounding box): 20 is 2 % of the part's size. Smaller values give many more pieces for little
// gain in a simulator (a 16 cm bowl: 63 pieces at 20, 163 at 1).
constexpr double kConcavity = 20;
constexpr size_t kMaxVerticesPerPiece = 64;
// A piece is flat when its thinnest principal spread is below this share of its widest.
constexpr double kFlatRatio = 1e-3;

bool HasVolume(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= double(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::Vector3d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                                     covariance, Eigen::EigenvaluesOnly)
                                     .eigenvalues();  // ascending, variances
  return spread[2] > 0 && std::sqrt(std::max(spread[0], 0.0) / spread[2]) > kFlatRatio;
}

void AddPiece(std::vector<Eigen::Vector3d> points, std::vector<ConvexPiece>& pieces) {
  points = CalcConvexHullVertices(points);
  if (HasVolume(points)) pieces.push_back(ConvexPiece{std::move(points)});
}

// HACD on one connected part that is not convex.
void DecomposeWithHacd(const TriangleMesh& part, std::vector<ConvexPiece>& pieces) {
  std::vector<HACD::Vec3<HACD::Real>> points;
  points.reserve(part.vertices_O.size());
  for (const Eigen::Vector3d& p : part.vertices_O) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<HACD::Vec3<long>> triangles;
  triangles.reserve(part.triangles.size());
  for (const Eigen::Vector3i& t : part.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  hacd.SetCompacityWeight(0.1);
  hacd.SetVolumeWeight(0.0);
  hacd.SetNClusters(1);
  hacd.SetNVerticesPerCH(kMaxVerticesPerPiece);
  hacd.SetConcavity(kConcavity);
  hacd.SetAddExtraDistPoints(true);
  hacd.SetAddNeighboursDistPoints(false);
  hacd.SetAddFacesPoints(true);
  if (!hacd.Compute()) {  // not expected for a part with triangles; keep the part's hull
    AddPiece(part.vertices_O, pieces);
    return;
  }
  for (size_t c = 0; c < hacd.GetNClusters(); ++c) {
    std::vector<HACD::Vec3<HACD::Real>> hull_points(hacd.GetNPointsCH(c));
    std::vector<HACD::Vec3<long>> hull_triangles(hacd.GetNTrianglesCH(c));
    if (hull_points.empty()) continue;
    hacd.GetCH(c, hull_points.data(), hull_triangles.data());
    std::vector<Eigen::Vector3d> piece;
    piece.reserve(hull_points.size());
    for (const auto& p : hull_points) piece.emplace_back(p.X(), p.Y(), p.Z());
    AddPiece(std::move(piece), pieces);
  }
}

std::vector<ConvexPiece> Decompose(const MeshShape& shape) {
  std::vector<ConvexPiece> pieces;
  const double tolerance = 1e-9 * std::max(1.0, shape.extents.maxCoeff());
  for (const TriangleMesh& part : SplitConnectedParts(shape.mesh)) {
    if (IsConvexSurface(part.vertices_O, part.triangles, tolerance)) {
      AddPiece(part.vertices_O, pieces);
    } else {
      DecomposeWithHacd(part, pieces);
    }
  }
  return pieces;
}

// The cache's key: the mesh's exact content (two files with the same triangles share pieces).
std::string ContentKey(const TriangleMesh& mesh) {
  std::string key;
  key.reserve(mesh.vertices_O.size() * sizeof(Eigen::Vector3d) +
              mesh.triangles.size() * sizeof(Eigen::Vector3i) + 16);
  const size_t counts[2] = {mesh.vertices_O.size(), mesh.triangles.size()};
  key.append(reinterpret_cast<const char*>(counts), sizeof counts);
  for (const Eigen::Vector3d& p : mesh.vertices_O)
    key.append(reinterpret_cast<const char*>(p.data()), sizeof(double) * 3);
  for (const Eigen::Vector3i& t : mesh.triangles)
    key.append(reinterpret_cast<const char*>(t.data()), sizeof(int) * 3);
  return key;
}

}  // namespace

bool IsConvexSurface(const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<Eigen::Vector3i>& triangles, double tolerance) {
  for (const Eigen::Vector3i& t : triangles) {
    const Eigen::Vector3d normal =
        (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
    const double length = normal.norm();
    if (!(length > 0)) continue;
    const Eigen::Vector3d n = normal / length;
    const double offset = n.dot(vertices[t[0]]);
    bool above = false, below = false;
    for (const Eigen::Vector3d& p : vertices) {
      const double d = n.dot(p) - offset;
      above = above || d > tolerance;
      below = below || d < -tolerance;
      if (above && below) return false;
    }
  }
  return true;
}

std::vector<TriangleMesh> SplitConnectedParts(const TriangleMesh& mesh) {
  // Union-find over vertices; each triangle joins its three.
  std::vector<int> parent(mesh.vertices_O.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Eigen::Vector3i& t : mesh.triangles) {
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  std::map<int, size_t> part_of_root;  // a root's index in `parts` (in order of first triangle)
  std::vector<TriangleMesh> parts;
  std::vector<int> renumber(mesh.vertices_O.size(), -1);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const int root = find(t[0]);
    auto [it, added] = part_of_root.emplace(root, parts.size());
    if (added) parts.emplace_back();
    TriangleMesh& part = parts[it->second];
    Eigen::Vector3i local;
    for (int k = 0; k < 3; ++k) {
      int& id = renumber[t[k]];
      if (id < 0) {
        id = static_cast<int>(part.vertices_O.size());
        part.vertices_O.push_back(mesh.vertices_O[t[k]]);
      }
      local[k] = id;
    }
    part.triangles.push_back(local);
  }
  return parts;
}

std::shared_ptr<const std::vector<ConvexPiece>> CalcConvexPieces(const MeshShape& shape) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const std::vector<ConvexPiece>>> cache;
  std::string key = ContentKey(shape.mesh);
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  auto pieces = std::make_shared<const std::vector<ConvexPiece>>(Decompose(shape));
  std::lock_guard<std::mutex> lock(mutex);
  return cache.emplace(std::move(key), std::move(pieces)).first->second;
}

}  // namespace prs::shapes
