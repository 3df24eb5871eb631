// Unions of convex pieces: the grid index, exact piecewise intersection with slice ownership,
// and exact sampling by measure (see union.h).
#include "geometry/union.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "geometry/polytope.h"

namespace prs::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Above this many pieces a PieceSet builds its grid index; below, a scan is as fast.
constexpr int kIndexThreshold = 16;
constexpr int kMaxGridCellsPerAxis = 64;
constexpr int kMaxBallRejections = 10000;

Eigen::AlignedBox3d InfiniteBox() {
  return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf));
}

// The bounding box of a region's canonical vertices; infinite when it is unbounded.
Eigen::AlignedBox3d CalcBounds(const ConvexRegion& region) {
  if (!region.IsBounded()) return InfiniteBox();
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : region.canon().vertices) box.extend(v);
  return box;
}

// The box grown by `margin` on every side (infinite boxes stay infinite).
Eigen::AlignedBox3d Grow(Eigen::AlignedBox3d box, double margin) {
  box.min().array() -= margin;
  box.max().array() += margin;
  return box;
}

bool IsBoxBeyond(const Eigen::AlignedBox3d& box, const HalfSpace& h) {
  // The least value of normal·x over the box exceeds the offset: the box is outside.
  double least = 0;
  for (int i = 0; i < 3; ++i) {
    least += h.normal[i] * (h.normal[i] > 0 ? box.min()[i] : box.max()[i]);
  }
  return std::isfinite(least) && least > h.offset + 1e-9;
}

// Whether the box lies wholly outside one of the region's half-spaces or equality planes.
bool IsBoxOutside(const Eigen::AlignedBox3d& box, const ConvexRegion& region) {
  for (const HalfSpace& h : region.half_spaces()) {
    if (IsBoxBeyond(box, h)) return true;
  }
  for (const HalfSpace& e : region.equalities()) {
    if (IsBoxBeyond(box, e) || IsBoxBeyond(box, {-e.normal, -e.offset})) return true;
  }
  return false;
}

bool IsLexicographicallyPositive(const Eigen::Vector3d& n) {
  for (int i = 0; i < 3; ++i) {
    if (std::abs(n[i]) > 1e-9) return n[i] > 0;
  }
  return true;
}

// Whether `slice` (a lower-dimensional part of `piece`) lies on a facet of the piece whose
// outward normal is lexicographically negative: that slice belongs to the neighbour across
// the facet (RegionUnion's half-open rule).
bool IsSliceOwnedByNeighbour(const ConvexRegion& piece, const ConvexRegion& slice) {
  const std::vector<Eigen::Vector3d>& vertices = slice.canon().vertices;
  if (vertices.empty()) return false;
  for (const HalfSpace& h : piece.half_spaces()) {
    if (IsLexicographicallyPositive(h.normal)) continue;
    const double tolerance = 1e-8 * std::max(1.0, std::abs(h.offset));
    const bool on_facet = std::all_of(vertices.begin(), vertices.end(), [&](const Eigen::Vector3d& v) {
      return std::abs(h.normal.dot(v) - h.offset) <= tolerance;
    });
    if (on_facet) return true;
  }
  return false;
}

std::string FormatNumber(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", x);
  return buffer;
}

// Intersections of `candidates` of `a` with region_L, appended to `out` with their dimensions.
struct Slice {
  ConvexRegion region;
  int dimension;
};

// The region with only the half-spaces that support a facet of it (and its equalities): the
// same set, cheaper to intersect with every piece. Regions whose canonical form collapsed a
// sliver or that have balls are returned as they are.
ConvexRegion KeepFacets(const ConvexRegion& region) {
  const internal::RegionCanon& c = region.canon();
  if (c.empty || c.contains_slack > 0 || !c.balls.empty() || c.dimension < 1) return region;
  std::vector<HalfSpace> facets;
  for (const HalfSpace& h : region.half_spaces()) {
    const double tolerance = 1e-9 * std::max(1.0, std::abs(h.offset));
    int touching = 0;
    for (const Eigen::Vector3d& v : c.vertices) touching += std::abs(h.normal.dot(v) - h.offset) <= tolerance;
    if (touching < c.dimension) continue;  // a facet holds at least `dimension` vertices
    const bool repeated = std::any_of(facets.begin(), facets.end(), [&](const HalfSpace& f) {
      return (f.normal - h.normal).norm() < 1e-12 && std::abs(f.offset - h.offset) < 1e-12;
    });
    if (!repeated) facets.push_back(h);
  }
  ConvexRegion simplified = ConvexRegion::FromHalfSpaces(facets);
  for (const HalfSpace& e : region.equalities()) {
    simplified = Intersect(simplified, ConvexRegion::MakePlane(e.normal * e.offset, e.normal));
  }
  return simplified;
}

// Whether some half-space of `piece` has every point of `vertices` strictly outside it: then
// the piece and the region with those vertices are disjoint.
bool IsSeparatedFrom(const ConvexRegion& piece, const std::vector<Eigen::Vector3d>& vertices) {
  for (const HalfSpace& h : piece.half_spaces()) {
    const double tolerance = 1e-9 * std::max(1.0, std::abs(h.offset));
    const bool outside = std::all_of(vertices.begin(), vertices.end(), [&](const Eigen::Vector3d& v) {
      return h.normal.dot(v) > h.offset + tolerance;
    });
    if (outside) return true;
  }
  return false;
}

// The region's vertices in frame L (empty when it is unbounded).
std::vector<Eigen::Vector3d> CalcVerticesIn(const ConvexRegion& region_W, const Eigen::Isometry3d& X_LW) {
  std::vector<Eigen::Vector3d> vertices;
  if (!region_W.IsBounded()) return vertices;
  for (const Eigen::Vector3d& v : region_W.canon().vertices) vertices.push_back(X_LW * v);
  return vertices;
}

// A planar region's polygon in its own plane's coordinates, for slicing pieces by clipping it
// instead of canonicalizing each slice from scratch (the slices lie in the same plane).
struct PlaneSlicer {
  AffineHull hull;
  std::vector<Eigen::Vector2d> polygon;  // counter-clockwise in hull coordinates
};

std::optional<PlaneSlicer> MakePlaneSlicer(const ConvexRegion& region) {
  const internal::RegionCanon& c = region.canon();
  if (c.empty || !c.bounded || c.dimension != 2 || c.contains_slack > 0 || !c.balls.empty()) {
    return std::nullopt;
  }
  PlaneSlicer slicer{c.hull, {}};
  for (const Eigen::Vector3d& v : c.vertices) {
    slicer.polygon.push_back(c.hull.basis.transpose() * (v - c.hull.p_origin));
  }
  return slicer;
}

enum class Clip { kEmpty, kSlice, kUndecided };

// piece ∩ region (planar, `slicer`'s) by clipping the region's polygon with the piece's
// half-spaces: the same set the general intersection gives, with its canonical form made here.
// kUndecided when a result touches or is as thin as the tolerances, which the general path's
// rules decide.
Clip SliceByClipping(const ConvexRegion& piece, const ConvexRegion& region, const PlaneSlicer& s,
                     ConvexRegion* slice) {
  if (!piece.equalities().empty() || !piece.balls().empty()) return Clip::kUndecided;
  std::vector<Eigen::Vector2d> polygon = s.polygon, scratch;
  for (const HalfSpace& h : piece.half_spaces()) {
    const Eigen::Vector2d a = s.hull.basis.transpose() * h.normal;
    const double b = h.offset - h.normal.dot(s.hull.p_origin), norm = a.norm();
    if (norm < 1e-9) {  // a face parallel to the plane: all of it or none of it satisfies
      if (b > 1e-8) continue;
      return b < -1e-8 ? Clip::kEmpty : Clip::kUndecided;
    }
    double least = std::numeric_limits<double>::infinity();  // metres, the most inside vertex
    for (const Eigen::Vector2d& p : polygon) least = std::min(least, (a.dot(p) - b) / norm);
    if (least > 1e-8) return Clip::kEmpty;
    if (least > -1e-8) return Clip::kUndecided;  // touching: the tolerance rules decide
    if (!internal::ClipPolygon(a, b, &polygon, &scratch)) return Clip::kUndecided;
  }
  double area = 0, longest = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    area += 0.5 * (p.x() * q.y() - q.x() * p.y());
    longest = std::max(longest, (q - p).norm());
    centroid += p / static_cast<double>(polygon.size());
  }
  // Thinner than a micrometre: the general path collapses slivers by its own rules.
  if (polygon.size() < 3 || !(area > 1e-6 * longest)) return Clip::kUndecided;
  internal::RegionCanon canon;
  canon.empty = false;
  canon.bounded = true;
  canon.dimension = 2;
  canon.hull = s.hull;
  for (const Eigen::Vector2d& p : polygon) canon.vertices.push_back(s.hull.p_origin + s.hull.basis * p);
  canon.polytope_measure = canon.measure = area;
  canon.measure_exact = true;
  canon.p_interior = s.hull.p_origin + s.hull.basis * centroid;
  *slice = internal::AttachCanon(Intersect(piece, region), std::move(canon));
  return Clip::kSlice;
}

void AppendSlices(const PieceSet& a, const ConvexRegion& region_L,
                  const std::vector<Eigen::Vector3d>& vertices_L, const Eigen::AlignedBox3d& query_L,
                  std::vector<Slice>* out) {
  std::vector<int> candidates;
  a.FindPiecesNear(query_L, &candidates);
  const std::optional<PlaneSlicer> slicer =
      candidates.empty() ? std::nullopt : MakePlaneSlicer(region_L);
  for (int i : candidates) {
    if (IsBoxOutside(a.bounds(i), region_L)) continue;
    const ConvexRegion& piece = a.pieces()[i];
    if (!vertices_L.empty() && IsSeparatedFrom(piece, vertices_L)) continue;
    ConvexRegion slice;
    const Clip clip = slicer ? SliceByClipping(piece, region_L, *slicer, &slice) : Clip::kUndecided;
    if (clip == Clip::kEmpty) continue;
    if (clip == Clip::kUndecided) slice = Intersect(piece, region_L);
    if (slice.IsEmpty()) continue;
    const int dimension = slice.dimension();
    if (dimension < piece.dimension() && IsSliceOwnedByNeighbour(piece, slice)) continue;
    out->push_back({std::move(slice), dimension});
  }
}

// The slices of the largest dimension, as a union in frame L.
RegionUnion MakeUnion(std::vector<Slice> slices, const Eigen::Isometry3d& X_WL) {
  int dimension = -1;
  for (const Slice& s : slices) dimension = std::max(dimension, s.dimension);
  std::vector<ConvexRegion> kept;
  kept.reserve(slices.size());
  for (Slice& s : slices) {
    if (s.dimension == dimension) kept.push_back(std::move(s.region));
  }
  return RegionUnion(std::make_shared<const PieceSet>(std::move(kept)), X_WL);
}

// The region's bounding box in frame L, from its world vertices.
Eigen::AlignedBox3d CalcBoundsIn(const ConvexRegion& region_W, const Eigen::Isometry3d& X_LW) {
  if (!region_W.IsBounded()) return InfiniteBox();
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : region_W.canon().vertices) box.extend(X_LW * v);
  return Grow(box, 1e-7);
}

}  // namespace

// ---------------------------------------------------------------------------
// PieceSet
// ---------------------------------------------------------------------------

PieceSet::PieceSet(std::vector<ConvexRegion> pieces) {
  pieces_.reserve(pieces.size());
  for (ConvexRegion& p : pieces) {
    if (p.IsEmpty()) continue;
    bounds_.push_back(CalcBounds(p));
    pieces_.push_back(std::move(p));
  }
  if (size() > kIndexThreshold) BuildIndex();
}

void PieceSet::BuildIndex() {
  for (int i = 0; i < size(); ++i) {
    if (bounds_[i].sizes().allFinite()) {
      grid_box_.extend(bounds_[i]);
    } else {
      unbounded_.push_back(i);
    }
  }
  if (grid_box_.isEmpty()) return;
  const Eigen::Vector3d extent = grid_box_.sizes().cwiseMax(1e-6);
  // About two cells per piece, shaped like the pieces' bounding box.
  const double cell = std::cbrt(extent.prod() / (2.0 * size()));
  for (int k = 0; k < 3; ++k) {
    grid_size_[k] = std::clamp(static_cast<int>(std::ceil(extent[k] / cell)), 1, kMaxGridCellsPerAxis);
    cell_size_[k] = extent[k] / grid_size_[k];
  }
  auto cell_range = [&](const Eigen::AlignedBox3d& box, Eigen::Vector3i* lo, Eigen::Vector3i* hi) {
    for (int k = 0; k < 3; ++k) {
      (*lo)[k] = std::clamp(static_cast<int>(std::floor((box.min()[k] - grid_box_.min()[k]) / cell_size_[k])),
                            0, grid_size_[k] - 1);
      (*hi)[k] = std::clamp(static_cast<int>(std::floor((box.max()[k] - grid_box_.min()[k]) / cell_size_[k])),
                            0, grid_size_[k] - 1);
    }
  };
  const int cells = grid_size_.prod();
  std::vector<int> count(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      cell_start_.assign(cells + 1, 0);
      for (int c = 0; c < cells; ++c) cell_start_[c + 1] = cell_start_[c] + count[c];
      cell_pieces_.resize(cell_start_[cells]);
      fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    }
    for (int i = 0; i < size(); ++i) {
      if (!bounds_[i].sizes().allFinite()) continue;
      Eigen::Vector3i lo, hi;
      cell_range(bounds_[i], &lo, &hi);
      for (int x = lo.x(); x <= hi.x(); ++x) {
        for (int y = lo.y(); y <= hi.y(); ++y) {
          for (int z = lo.z(); z <= hi.z(); ++z) {
            const int c = (x * grid_size_.y() + y) * grid_size_.z() + z;
            if (pass == 0) {
              ++count[c];
            } else {
              cell_pieces_[fill[c]++] = i;
            }
          }
        }
      }
    }
  }
}

void PieceSet::FindPiecesNear(const Eigen::AlignedBox3d& query, std::vector<int>* out) const {
  const size_t first = out->size();
  if (cell_start_.empty()) {
    for (int i = 0; i < size(); ++i) {
      if (bounds_[i].intersects(query)) out->push_back(i);
    }
    return;
  }
  out->insert(out->end(), unbounded_.begin(), unbounded_.end());
  if (query.intersects(grid_box_)) {
    Eigen::Vector3i lo, hi;
    for (int k = 0; k < 3; ++k) {
      const double a = (std::max(query.min()[k], grid_box_.min()[k]) - grid_box_.min()[k]) / cell_size_[k];
      const double b = (std::min(query.max()[k], grid_box_.max()[k]) - grid_box_.min()[k]) / cell_size_[k];
      lo[k] = std::clamp(static_cast<int>(std::floor(a)), 0, grid_size_[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor(b)), 0, grid_size_[k] - 1);
    }
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int z = lo.z(); z <= hi.z(); ++z) {
          const int c = (x * grid_size_.y() + y) * grid_size_.z() + z;
          for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
            if (bounds_[cell_pieces_[k]].intersects(query)) out->push_back(cell_pieces_[k]);
          }
        }
      }
    }
  }
  std::sort(out->begin() + first, out->end());
  out->erase(std::unique(out->begin() + first, out->end()), out->end());
}

// ---------------------------------------------------------------------------
// RegionUnion
// ---------------------------------------------------------------------------

RegionUnion::RegionUnion() : pieces_(std::make_shared<const PieceSet>(std::vector<ConvexRegion>{})) {}

RegionUnion::RegionUnion(std::shared_ptr<const PieceSet> pieces, const Eigen::Isometry3d& X_WL)
    : pieces_(std::move(pieces)), X_WL_(X_WL) {
  if (!pieces_) pieces_ = std::make_shared<const PieceSet>(std::vector<ConvexRegion>{});
}

RegionUnion RegionUnion::FromConvex(const ConvexRegion& region_W) {
  return RegionUnion(std::make_shared<const PieceSet>(std::vector<ConvexRegion>{region_W}));
}

bool RegionUnion::IsBounded() const {
  return std::all_of(pieces_->pieces().begin(), pieces_->pieces().end(),
                     [](const ConvexRegion& p) { return p.IsBounded(); });
}

int RegionUnion::dimension() const {
  int dimension = -1;
  for (const ConvexRegion& p : pieces_->pieces()) dimension = std::max(dimension, p.dimension());
  return dimension;
}

bool RegionUnion::Contains(const Eigen::Vector3d& p_W, double tolerance) const {
  if (!p_W.allFinite()) return false;
  const Eigen::Vector3d p_L = X_WL_.inverse() * p_W;
  std::vector<int> candidates;
  pieces_->FindPiecesNear(Grow(Eigen::AlignedBox3d(p_L, p_L), std::max(tolerance, 0.0) + 1e-9),
                          &candidates);
  return std::any_of(candidates.begin(), candidates.end(),
                     [&](int i) { return pieces_->pieces()[i].Contains(p_L, tolerance); });
}

double RegionUnion::CalcMeasure() const {
  const int top = dimension();
  double total = 0;
  for (const ConvexRegion& p : pieces_->pieces()) {
    if (p.dimension() == top) total += p.CalcMeasure();
  }
  return total;
}

std::string RegionUnion::Describe() const {
  if (IsEmpty()) return "empty union of convex pieces";
  std::string text = num_pieces() == 1 ? "one convex piece" :
                     "a union of " + std::to_string(num_pieces()) + " convex pieces";
  if (!IsBounded()) return text + " (unbounded)";
  try {
    static const char* kUnits[] = {"", " m", " m²", " m³"};
    const int d = dimension();
    if (d > 0) text += ", " + FormatNumber(CalcMeasure()) + kUnits[d] + " in all";
  } catch (const std::domain_error&) {
    // pieces with balls have no exact measure; leave it out
  }
  return text;
}

ConvexRegion TransformRegion(const ConvexRegion& region_A, const Eigen::Isometry3d& X_BA) {
  if (region_A.IsEmpty()) return ConvexRegion::Empty();
  const Eigen::Matrix3d R = X_BA.linear();
  const Eigen::Vector3d t = X_BA.translation();
  // n·x_A <= d  <=>  (R n)·x_B <= d + (R n)·t, since x_A = Rᵀ (x_B − t).
  std::vector<HalfSpace> half_spaces = region_A.half_spaces();
  for (HalfSpace& h : half_spaces) {
    h.normal = R * h.normal;
    h.offset += h.normal.dot(t);
  }
  ConvexRegion result = ConvexRegion::FromHalfSpaces(half_spaces);
  for (const HalfSpace& e : region_A.equalities()) {
    const Eigen::Vector3d n_B = R * e.normal;
    result = Intersect(result, ConvexRegion::MakePlane(n_B * (e.offset + n_B.dot(t)), n_B));
  }
  for (const Ball& b : region_A.balls()) {
    result = Intersect(result, ConvexRegion::MakeSphere(X_BA * b.p_center, b.radius));
  }
  return result;
}

RegionUnion Intersect(const RegionUnion& a, const ConvexRegion& b_W) {
  if (a.IsEmpty() || b_W.IsEmpty()) return RegionUnion();
  const Eigen::Isometry3d X_LW = a.X_WL().inverse();
  const ConvexRegion b_L = TransformRegion(KeepFacets(b_W), X_LW);
  std::vector<Slice> slices;
  AppendSlices(a.piece_set(), b_L, CalcVerticesIn(b_W, X_LW), CalcBoundsIn(b_W, X_LW), &slices);
  return MakeUnion(std::move(slices), a.X_WL());
}

RegionUnion Intersect(const RegionUnion& a, const RegionUnion& b) {
  if (a.IsEmpty() || b.IsEmpty()) return RegionUnion();
  const Eigen::Isometry3d X_LbW = b.X_WL().inverse();
  std::vector<Slice> slices;
  for (const ConvexRegion& piece_a : a.piece_set().pieces()) {
    const ConvexRegion piece_W = TransformRegion(piece_a, a.X_WL());
    const ConvexRegion piece_Lb = TransformRegion(piece_a, X_LbW * a.X_WL());
    std::vector<Slice> part;
    AppendSlices(b.piece_set(), piece_Lb, CalcVerticesIn(piece_W, X_LbW),
                 CalcBoundsIn(piece_W, X_LbW), &part);
    // A slice on a facet of a's piece is owned by one of a's pieces only, likewise.
    for (Slice& s : part) {
      if (s.dimension < piece_Lb.dimension() && IsSliceOwnedByNeighbour(piece_Lb, s.region)) continue;
      slices.push_back(std::move(s));
    }
  }
  return MakeUnion(std::move(slices), b.X_WL());
}

// ---------------------------------------------------------------------------
// UnionSampler
// ---------------------------------------------------------------------------

UnionSampler::UnionSampler(const RegionUnion& region) : X_WL_(region.X_WL()) {
  if (region.IsEmpty()) throw std::domain_error("UnionSampler: cannot sample an empty union");
  if (!region.IsBounded()) {
    throw std::domain_error("UnionSampler: cannot sample an unbounded union: " + region.Describe());
  }
  dimension_ = region.dimension();
  double total = 0;
  for (const ConvexRegion& piece : region.piece_set().pieces()) {
    if (piece.dimension() != dimension_) continue;
    const internal::RegionCanon& c = piece.canon();
    has_balls_ = has_balls_ || !c.balls.empty();
    total += dimension_ == 0 ? 1.0 : (c.measure_exact ? c.measure : c.polytope_measure);
    pieces_.push_back(piece);
    cumulative_.push_back(total);
  }
  samplers_.resize(pieces_.size());
}

const UnionSampler& UnionSampler::BuildAll() const {
  for (int i = 0; i < num_pieces(); ++i) piece_sampler(i);
  return *this;
}

const RegionSampler& UnionSampler::piece_sampler(int i) const {
  if (!samplers_[i]) samplers_[i] = std::make_unique<RegionSampler>(pieces_[i]);
  return *samplers_[i];
}

int UnionSampler::PickPiece(double u) const {
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u);
  return std::min(static_cast<int>(it - cumulative_.begin()), num_pieces() - 1);
}

Eigen::Vector3d UnionSampler::Sample(Rng& rng) const {
  for (int attempt = 0; attempt < kMaxBallRejections; ++attempt) {
    const RegionSampler& s = piece_sampler(PickPiece(rng.Uniform(0, measure())));
    const Eigen::Vector3d p_L = s.SamplePolytopePart(rng);
    if (!has_balls_ || s.IsInBalls(p_L)) return ToWorld(p_L);
  }
  throw std::domain_error("UnionSampler: region too thin to sample (" +
                          std::to_string(kMaxBallRejections) + " points rejected by its balls)");
}

}  // namespace prs::geometry
