// The scene's collision checks (spec §6: objects do not overlap unless one allows it): each
// object, once made, against the collidable objects made before it. Past a few dozen objects a
// broad phase (a horizontal grid of their bounding balls) keeps a run's checks growing about
// linearly with its objects instead of quadratically. The objects tested are always taken in
// index order, so the rejection names the same pair as testing every object would.
#include <algorithm>
#include <cmath>

#include "lang/interp_internal.h"

namespace prs::lang::internal {
namespace {

constexpr double kCellM = 0.25;  // the grid's cell side

// The radius of the ball around the box, as DoObjectsOverlap's first test.
double CalcReach(const SceneObject& o) { return o.dimensions.norm() / 2; }

int64_t CellOf(double x) { return static_cast<int64_t>(std::floor(x / kCellM)); }

uint64_t CellKey(int64_t i, int64_t j) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(i)) << 32) | static_cast<uint32_t>(j);
}

// Whether an object's ball is filed in cells (else it is tested against every object): small
// enough, and where cell numbers cannot overflow.
bool IsGridded(const SceneObject& o, double reach) {
  return reach <= kCellM && std::fabs(o.p_WO.x()) < 1e6 && std::fabs(o.p_WO.y()) < 1e6;
}

// Calls visit(key) for each cell the square around the ball at `o` overlaps.
template <typename Visit>
void ForEachCell(const SceneObject& o, double reach, Visit visit) {
  const int64_t i0 = CellOf(o.p_WO.x() - reach), i1 = CellOf(o.p_WO.x() + reach);
  const int64_t j0 = CellOf(o.p_WO.y() - reach), j1 = CellOf(o.p_WO.y() + reach);
  for (int64_t i = i0; i <= i1; ++i) {
    for (int64_t j = j0; j <= j1; ++j) visit(CellKey(i, j));
  }
}

}  // namespace

void Interpreter::CheckCollisions(int index) {
  const SceneObject& o = scene_.objects[index];
  if (!o.cls->has_box || o.allow_collisions) return;
  CollisionGrid& grid = collision_grid_;
  if (!grid.built && grid.collidable >= std::max(1, options_.collision_grid_from)) BuildGrid(index);
  const double reach = CalcReach(o);
  if (grid.built && IsGridded(o, reach)) {
    std::vector<int>& candidates = grid.candidates;
    candidates = grid.large;
    ForEachCell(o, reach, [&](uint64_t key) {
      auto it = grid.cells.find(key);
      if (it != grid.cells.end()) {
        candidates.insert(candidates.end(), it->second.begin(), it->second.end());
      }
    });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (int other : candidates) {
      if (other != index && DoObjectsOverlap(index, other)) RejectCollision(index, other);
    }
  } else {
    for (int other = 0; other < static_cast<int>(scene_.objects.size()); ++other) {
      if (other != index && IsCollidable(other) && DoObjectsOverlap(index, other)) {
        RejectCollision(index, other);
      }
    }
  }
  ++grid.collidable;
  if (grid.built) AddToCollisionGrid(index);
}

bool Interpreter::IsCollidable(int index) const {
  const SceneObject& o = scene_.objects[index];
  return completed_[index] && o.cls->has_box && !o.allow_collisions;
}

void Interpreter::BuildGrid(int checking) {
  collision_grid_.built = true;
  for (int k = 0; k < static_cast<int>(scene_.objects.size()); ++k) {
    if (k != checking && IsCollidable(k)) AddToCollisionGrid(k);
  }
}

void Interpreter::AddToCollisionGrid(int index) {
  CollisionGrid& grid = collision_grid_;
  const SceneObject& o = scene_.objects[index];
  const double reach = CalcReach(o);
  if (!IsGridded(o, reach)) {
    grid.large.push_back(index);
    return;
  }
  ForEachCell(o, reach, [&](uint64_t key) { grid.cells[key].push_back(index); });
}

void Interpreter::RejectCollision(int index, int other) {
  const int first = std::min(index, other), second = std::max(index, other);
  std::string culprit = scene_.objects[first].DisplayName(first) + " and " +
                        scene_.objects[second].DisplayName(second);
  std::string detail = IsExplained(RejectionKind::kCollision, culprit)
                           ? ""
                           : DescribeBox(first) + " overlaps " + DescribeBox(second);
  Reject(RejectionKind::kCollision, std::move(culprit), scene_.objects[index].span,
         std::move(detail));
}

}  // namespace prs::lang::internal
