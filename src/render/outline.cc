// The workspace outline: edges of a bounded convex region from its vertices and constraints.
// Two vertices of a polyhedron span an edge when they lie together on two distinct faces.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/scene_input.h"

namespace prs::render {
namespace {

constexpr double kOnPlaneTolerance = 1e-6;  // metres

// The indices of the distinct half-spaces whose planes pass through `p`.
std::vector<int> FindActivePlanes(const Eigen::Vector3d& p,
                                  const std::vector<geometry::HalfSpace>& planes) {
  std::vector<int> active;
  for (int i = 0; i < static_cast<int>(planes.size()); ++i) {
    if (std::abs(planes[i].normal.dot(p) - planes[i].offset) < kOnPlaneTolerance)
      active.push_back(i);
  }
  return active;
}

// The half-spaces with duplicates (same normal and offset) removed, so that two vertices of
// one face never count that face twice.
std::vector<geometry::HalfSpace> DeduplicatePlanes(const std::vector<geometry::HalfSpace>& all) {
  std::vector<geometry::HalfSpace> distinct;
  for (const geometry::HalfSpace& h : all) {
    bool seen = false;
    for (const geometry::HalfSpace& d : distinct) {
      seen |= (h.normal - d.normal).norm() < 1e-9 && std::abs(h.offset - d.offset) < 1e-9;
    }
    if (!seen) distinct.push_back(h);
  }
  return distinct;
}

int CountShared(const std::vector<int>& a, const std::vector<int>& b) {
  int shared = 0;
  for (int i : a) shared += std::count(b.begin(), b.end(), i);
  return shared;
}

std::vector<Segment> CalcPolyhedronEdges(const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<geometry::HalfSpace>& half_spaces) {
  const std::vector<geometry::HalfSpace> planes = DeduplicatePlanes(half_spaces);
  std::vector<std::vector<int>> active;
  for (const Eigen::Vector3d& v : vertices) active.push_back(FindActivePlanes(v, planes));
  std::vector<Segment> edges;
  for (size_t i = 0; i < vertices.size(); ++i) {
    for (size_t j = i + 1; j < vertices.size(); ++j) {
      if (CountShared(active[i], active[j]) >= 2) edges.emplace_back(vertices[i], vertices[j]);
    }
  }
  return edges;
}

}  // namespace

std::vector<Segment> CalcOutlineEdges(const geometry::ConvexRegion& region) {
  if (region.IsEmpty() || !region.IsBounded()) return {};
  const int dimension = region.dimension();
  std::vector<Eigen::Vector3d> vertices;
  try {
    vertices = region.CalcVertices();
  } catch (const std::domain_error&) {
    return {};
  }
  if (dimension == 3) return CalcPolyhedronEdges(vertices, region.half_spaces());
  std::vector<Segment> edges;  // a polygon's vertices come in cyclic order; a segment's two
  if (dimension == 1 && vertices.size() == 2) edges.emplace_back(vertices[0], vertices[1]);
  if (dimension == 2) {
    for (size_t i = 0; i < vertices.size(); ++i)
      edges.emplace_back(vertices[i], vertices[(i + 1) % vertices.size()]);
  }
  return edges;
}

}  // namespace prs::render
