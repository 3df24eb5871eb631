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

size_t HashCell(uint64_t key, size_t buckets) {
  return static_cast<size_t>((key * 0x9E3779B97F4A7C15ULL) >> 32) & (buckets - 1);
}

// Files `object` under `cell`, doubling the buckets when there are as many pairs as buckets.
void FileInCell(CollisionGrid& grid, uint64_t cell, int object) {
  if (grid.entries.size() >= grid.heads.size()) {
    grid.heads.assign(grid.heads.size() * 2, -1);
    for (size_t e = 0; e < grid.entries.size(); ++e) {
      const size_t h = HashCell(grid.entries[e].cell, grid.heads.size());
      grid.entries[e].next = grid.heads[h];
      grid.heads[h] = static_cast<int>(e);
    }
  }
  const size_t h = HashCell(cell, grid.heads.size());
  grid.entries.push_back({cell, object, grid.heads[h]});
  grid.heads[h] = static_cast<int>(grid.entries.size() - 1);
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
  if (!o.cls->has_box || o.allow_collisions || !options_.check_collisions) return;
  CollisionGrid& grid = collision_grid_;
  if (!grid.built && grid.collidable >= std::max(1, options_.collision_grid_from)) BuildGrid(index);
  const double reach = CalcReach(o);
  if (grid.built && IsGridded(o, reach)) {
    std::vector<int>& candidates = grid.candidates;
    candidates = grid.large;
    ForEachCell(o, reach, [&](uint64_t key) {
      for (int e = grid.heads[HashCell(key, grid.heads.size())]; e >= 0; e = grid.entries[e].next) {
        if (grid.entries[e].cell == key) candidates.push_back(grid.entries[e].object);
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
  size_t buckets = 256;  // a few cells an object, for the objects so far
  while (buckets < 8 * scene_.objects.size()) buckets *= 2;
  collision_grid_.heads.assign(buckets, -1);
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
  ForEachCell(o, reach, [&](uint64_t key) { FileInCell(grid, key, index); });
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

namespace prs::lang {

bool DoObjectsCollide(const SceneObject& a, const SceneObject& b, RunCache* cache) {
  if (!a.cls->has_box || !b.cls->has_box || a.allow_collisions || b.allow_collisions) return false;
  return internal::DoPlacedObjectsOverlap(a, b, cache);
}

}  // namespace prs::lang
