// Finite unions of convex pieces with disjoint interiors (spec §10): the regions that
// `reachable by` and `not in view of` give, intersected exactly piece by piece and sampled
// exactly (a piece by measure, then a uniform point in it). Pieces live in a local frame L
// placed in the world by X_WL, so one union (an arm's reachable cells in its base frame)
// serves every pose of its owner without moving thousands of pieces.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/random.h"
#include "geometry/region.h"
#include "geometry/sampling.h"

namespace prs::geometry {

/// An immutable list of convex pieces in one frame, with their bounding boxes and a grid index
/// for finding the pieces near a query box. Pieces must have pairwise disjoint interiors (not
/// checked: that would cost O(n²)); each is finalized on construction, so a PieceSet may be
/// shared by any number of threads.
class PieceSet {
 public:
  /// Takes the pieces; empty ones are dropped. Pieces may be unbounded.
  explicit PieceSet(std::vector<ConvexRegion> pieces);

  const std::vector<ConvexRegion>& pieces() const { return pieces_; }
  int size() const { return static_cast<int>(pieces_.size()); }
  /// The bounding box of piece i (infinite extents for an unbounded piece).
  const Eigen::AlignedBox3d& bounds(int i) const { return bounds_[i]; }
  /// Appends the indices of the pieces whose bounding box meets `query` (in increasing order).
  void FindPiecesNear(const Eigen::AlignedBox3d& query, std::vector<int>* out) const;

 private:
  void BuildIndex();

  std::vector<ConvexRegion> pieces_;
  std::vector<Eigen::AlignedBox3d> bounds_;
  // A uniform grid over the bounded pieces' boxes: cell c lists the pieces meeting it.
  Eigen::AlignedBox3d grid_box_;
  Eigen::Vector3i grid_size_ = Eigen::Vector3i::Zero();
  Eigen::Vector3d cell_size_ = Eigen::Vector3d::Ones();
  std::vector<int> cell_start_;  // CSR: pieces of cell c are cell_pieces_[start[c]..start[c+1])
  std::vector<int> cell_pieces_;
  std::vector<int> unbounded_;  // pieces every query returns
};

/// A union of convex pieces (a PieceSet, shared) placed in the world by X_WL. A cheap value
/// type. The pieces are read as half-open cells: where a lower-dimensional region lies on a
/// facet two pieces share, the slice belongs to the piece whose facet's outward normal is
/// lexicographically positive (its first non-zero component is positive), so slices of
/// adjacent pieces never overlap.
class RegionUnion {
 public:
  /// The empty union.
  RegionUnion();
  /// The union of `pieces` (in frame L) placed by X_WL.
  RegionUnion(std::shared_ptr<const PieceSet> pieces,
              const Eigen::Isometry3d& X_WL = Eigen::Isometry3d::Identity());
  /// A union of one convex piece (world frame).
  static RegionUnion FromConvex(const ConvexRegion& region_W);

  const PieceSet& piece_set() const { return *pieces_; }
  const std::shared_ptr<const PieceSet>& shared_pieces() const { return pieces_; }
  int num_pieces() const { return pieces_->size(); }
  const Eigen::Isometry3d& X_WL() const { return X_WL_; }

  /// True when there is no piece.
  bool IsEmpty() const { return pieces_->size() == 0; }
  /// True when every piece is bounded.
  bool IsBounded() const;
  /// The largest dimension of a piece (-1 when empty).
  int dimension() const;
  /// True when some piece contains p_W within `tolerance` (metres).
  bool Contains(const Eigen::Vector3d& p_W, double tolerance = kGeometricTolerance) const;
  /// The sum of the pieces' measures (their own dimension). Throws std::domain_error as
  /// ConvexRegion::CalcMeasure does for pieces with balls cut by other constraints.
  double CalcMeasure() const;
  /// A short description for diagnostics, e.g. "a union of 12 convex pieces, 0.031 m² in all".
  std::string Describe() const;

 private:
  std::shared_ptr<const PieceSet> pieces_;
  Eigen::Isometry3d X_WL_ = Eigen::Isometry3d::Identity();
};

/// The region in frame B of a region given in frame A (exact: every constraint is moved).
ConvexRegion TransformRegion(const ConvexRegion& region_A, const Eigen::Isometry3d& X_BA);

/// The union ∩ a convex region given in the world frame, in the union's frame L: each piece
/// near the region intersected with it exactly. Empty intersections, intersections of lower
/// dimension than the largest, and slices a piece does not own (see RegionUnion) are dropped.
RegionUnion Intersect(const RegionUnion& a, const ConvexRegion& b_W);

/// The intersection of two unions, in b's frame: each piece of `a` (moved into b's frame)
/// intersected with `b`.
RegionUnion Intersect(const RegionUnion& a, const RegionUnion& b);

/// Exact uniform sampling over a bounded union: a piece is picked in proportion to its
/// measure, then a uniform point of it (RegionSampler). Pieces with balls are weighted by
/// their polytope part, and a point outside a ball restarts the whole draw (piece and point),
/// which keeps the law exact. A piece's RegionSampler is built when first used; call BuildAll()
/// before sharing a sampler between threads.
class UnionSampler {
 public:
  /// Throws std::domain_error when the union is empty or a piece is unbounded.
  explicit UnionSampler(const RegionUnion& region);

  /// Builds every piece's sampler now; afterwards all const calls are thread-safe.
  const UnionSampler& BuildAll() const;
  /// One uniform point (world frame). Throws std::domain_error ("region too thin to sample")
  /// after 10,000 consecutive rejections by balls.
  Eigen::Vector3d Sample(Rng& rng) const;
  /// The index of the piece that `u` of [0, measure()) falls in (by cumulative measure).
  int PickPiece(double u) const;
  /// Piece i's sampler, in the union's frame L (built on first use).
  const RegionSampler& piece_sampler(int i) const;
  /// p_L moved into the world.
  Eigen::Vector3d ToWorld(const Eigen::Vector3d& p_L) const { return X_WL_ * p_L; }

  int dimension() const { return dimension_; }
  int num_pieces() const { return static_cast<int>(pieces_.size()); }
  /// The pieces sampled (those of the largest dimension), in frame L.
  const std::vector<ConvexRegion>& pieces() const { return pieces_; }
  const Eigen::Isometry3d& X_WL() const { return X_WL_; }
  /// The sum of the pieces' measures (polytope parts when has_balls()).
  double measure() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
  bool has_balls() const { return has_balls_; }

 private:
  std::vector<ConvexRegion> pieces_;  // in L
  mutable std::vector<std::unique_ptr<RegionSampler>> samplers_;
  std::vector<double> cumulative_;  // running sums of the pieces' (polytope) measures
  Eigen::Isometry3d X_WL_ = Eigen::Isometry3d::Identity();
  int dimension_ = -1;
  bool has_balls_ = false;
};

}  // namespace prs::geometry
