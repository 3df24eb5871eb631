// Convex cells from reachability grids (see reach_internal.h): for symmetric chains, per
// elementary arc of azimuths, the (r, z) cells covering it grown row by row into trapezoids
// with slanted sides, each turned about the base's z axis into annular-sector cells; for the
// other chains, boxes.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "geometry/check.h"
#include "kinematics/reach_internal.h"

namespace prs::kinematics::internal {

namespace {

using geometry::ConvexRegion;
using geometry::HalfSpace;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Azimuths.

// An arc of azimuths [begin, end] (radians), or the whole circle.
struct Arc {
  double begin = 0, end = 0;
  bool full = false;
};

// Joint 1's range as azimuths of sheet 0's forward cells, [a, b].
std::pair<double, double> CalcForwardArc(const Symmetry& s) {
  return s.sign > 0 ? std::make_pair(s.lower, s.upper) : std::make_pair(-s.upper, -s.lower);
}

// The arcs every label bit sweeps (bit 2k: forward in sheet k, bit 2k+1: backward).
std::vector<Arc> CalcBitArcs(const std::vector<double>& sheet_rad, const Symmetry& s) {
  const auto [a, b] = CalcForwardArc(s);
  std::vector<Arc> arcs;
  for (double psi : sheet_rad) {
    arcs.push_back({psi + a, psi + b, TurnsAllTheWay(s)});
    arcs.push_back({psi + a + kPi, psi + b + kPi, TurnsAllTheWay(s)});
  }
  return arcs;
}

double Wrap(double angle) { return angle - 2 * kPi * std::floor(angle / (2 * kPi)); }

// The circle cut at every end of every bit's arc: the elementary arcs, each either inside or
// outside each bit's arc. One full circle when joint 1 turns all the way round.
std::vector<Arc> CalcElementaryArcs(const std::vector<Arc>& bit_arcs) {
  std::vector<double> cuts;
  for (const Arc& arc : bit_arcs) {
    if (arc.full) continue;
    cuts.push_back(Wrap(arc.begin));
    cuts.push_back(Wrap(arc.end));
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> unique;
  for (double c : cuts) {
    if (unique.empty() || c - unique.back() > 1e-9) unique.push_back(c);
  }
  if (unique.size() > 1 && unique.front() + 2 * kPi - unique.back() <= 1e-9) unique.pop_back();
  if (unique.empty()) return {{0, 2 * kPi, true}};
  std::vector<Arc> elementary;
  for (size_t i = 0; i < unique.size(); ++i) {
    const double end = i + 1 < unique.size() ? unique[i + 1] : unique[0] + 2 * kPi;
    elementary.push_back({unique[i], end, false});
  }
  return elementary;
}

bool IsInArc(double angle, const Arc& arc) {
  return arc.full || Wrap(angle - arc.begin) <= arc.end - arc.begin;
}

// Which elementary arcs a label's azimuths cover, one bit each (memoized per label).
class CoverTable {
 public:
  CoverTable(std::vector<Arc> bit_arcs, const std::vector<Arc>& elementary)
      : bit_arcs_(std::move(bit_arcs)), elementary_(elementary) {}
  uint64_t Cover(uint32_t label) {
    if (const auto it = memo_.find(label); it != memo_.end()) return it->second;
    uint64_t mask = 0;
    for (size_t e = 0; e < elementary_.size(); ++e) {
      const double mid = 0.5 * (elementary_[e].begin + elementary_[e].end);
      for (size_t bit = 0; bit < bit_arcs_.size(); ++bit) {
        if ((label >> bit & 1) && IsInArc(mid, bit_arcs_[bit])) mask |= uint64_t{1} << e;
      }
    }
    return memo_[label] = mask;
  }

 private:
  std::vector<Arc> bit_arcs_;
  const std::vector<Arc>& elementary_;
  std::map<uint32_t, uint64_t> memo_;
};

// True when `cover` holds elementary arc e and, with a margin, reaches on past both its ends by
// the angle a ball of radius margin around a point at distance r_min from the axis spans.
bool Covers(uint64_t cover, int e, const std::vector<Arc>& elementary, double margin,
            double r_min) {
  const int n = static_cast<int>(elementary.size());
  if (!(cover >> e & 1)) return false;
  if (margin <= 0) return true;
  const uint64_t all = n == 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1;
  if (cover == all) return true;
  if (r_min <= margin) return false;  // the ball holds the axis: every azimuth is needed
  const double spread = std::asin(margin / r_min);
  for (int step : {-1, 1}) {
    double reach = 0;
    for (int k = 1; k < n && reach < spread; ++k) {
      const int next = ((e + step * k) % n + n) % n;
      if (!(cover >> next & 1)) return false;
      reach += elementary[next].end - elementary[next].begin;
    }
    if (reach < spread) return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Trapezoids in (r, z).

// One run of radial cells [r0, r1) of a row.
struct Span {
  int r0, r1;
};

// The runs of radial cells of a row that cover elementary arc e.
std::vector<Span> CalcRowSpans(const std::vector<CellGrid>& sheets, int row, int e,
                               const std::vector<Arc>& elementary, double margin,
                               CoverTable& table) {
  const int half = -sheets[0].origin[0];  // the cells at x >= 0
  const double res = sheets[0].resolution_m;
  std::vector<Span> spans;
  for (int r = 0; r < half; ++r) {
    uint32_t label = 0;
    for (size_t k = 0; k < sheets.size(); ++k) {
      label |= (sheets[k].is_in(half + r, 0, row) ? 1u : 0u) << (2 * k);
      label |= (sheets[k].is_in(half - r - 1, 0, row) ? 1u : 0u) << (2 * k + 1);
    }
    if (!label || !Covers(table.Cover(label), e, elementary, margin, r * res)) continue;
    if (!spans.empty() && spans.back().r1 == r) {
      spans.back().r1 = r + 1;
    } else {
      spans.push_back({r, r + 1});
    }
  }
  return spans;
}

// r = c + d·z.
struct Line {
  double c = 0, d = 0;
  double at(double z) const { return c + d * z; }
};

// The line through the points (z_j, y_j) (z increasing) that stays below (upper = false) or
// above (upper = true) all of them and is highest (lowest) at z_mid: an edge of their lower
// (upper) convex hull.
Line FitLine(const std::vector<double>& z, const std::vector<double>& y, double z_mid, bool upper) {
  const double sign = upper ? -1 : 1;  // an upper hull is the lower hull of −y
  std::vector<int> hull;
  for (int j = 0; j < static_cast<int>(z.size()); ++j) {
    while (hull.size() >= 2) {
      const int a = hull[hull.size() - 2], b = hull.back();
      const double cross =
          (z[b] - z[a]) * (sign * y[j] - sign * y[a]) - (sign * y[b] - sign * y[a]) * (z[j] - z[a]);
      if (cross > 0) break;  // a left turn keeps b on the lower hull
      hull.pop_back();
    }
    hull.push_back(j);
  }
  for (size_t h = 0; h + 1 < hull.size(); ++h) {
    const int a = hull[h], b = hull[h + 1];
    if (z[b] >= z_mid || h + 2 == hull.size()) {
      const double d = (y[b] - y[a]) / (z[b] - z[a]);
      return {y[a] - d * z[a], d};
    }
  }
  return {y[hull[0]], 0};
}

// A run of rows whose spans follow one another, and the trapezoid inside them.
struct Piece {
  int row0 = 0;
  std::vector<Span> spans;  // one per row from row0
  Line inner, outer;        // metres, over z in metres
  double z0 = 0, z1 = 0;
};

// Fits the piece's two sides. False when the trapezoid would lose more of the rows' cells than
// their staircase edges do (about half a cell per row, plus half of each step), or pinch.
bool FitPiece(Piece& piece, double res, int origin_z) {
  const int rows = static_cast<int>(piece.spans.size());
  std::vector<double> z(rows + 1), y_in(rows + 1), y_out(rows + 1);
  double staircase = 0, allowed = 0;
  for (int j = 0; j <= rows; ++j) {
    z[j] = (origin_z + piece.row0 + j) * res;
    const Span& below = piece.spans[std::max(j - 1, 0)];
    const Span& above = piece.spans[std::min(j, rows - 1)];
    y_in[j] = std::max(below.r0, above.r0) * res;
    y_out[j] = std::min(below.r1, above.r1) * res;
    if (y_out[j] <= y_in[j]) return false;
    if (j < rows) {
      staircase += (piece.spans[j].r1 - piece.spans[j].r0) * res * res;
      allowed += 0.5 * res * res;
    }
    if (j > 0 && j < rows) {
      allowed += 0.5 * res * (std::abs(above.r0 - below.r0) + std::abs(above.r1 - below.r1)) * res;
    }
  }
  piece.z0 = z.front(), piece.z1 = z.back();
  const double z_mid = 0.5 * (piece.z0 + piece.z1);
  piece.outer = FitLine(z, y_out, z_mid, false);
  piece.inner = FitLine(z, y_in, z_mid, true);
  for (double at : {piece.z0, piece.z1}) {
    if (piece.outer.at(at) - piece.inner.at(at) < 0.5 * res) return false;
  }
  const double area = (piece.z1 - piece.z0) * (piece.outer.at(z_mid) - piece.inner.at(z_mid));
  return staircase - area <= allowed + 1e-15;
}

// Grows pieces bottom-up over the cells that cover elementary arc e: a piece takes the next
// row's span when they overlap one-to-one and the trapezoid still fits; otherwise it ends and
// the span starts a new one.
std::vector<Piece> BuildPieces(const std::vector<CellGrid>& sheets, int e,
                               const std::vector<Arc>& elementary, double margin,
                               CoverTable& table) {
  const double res = sheets[0].resolution_m;
  const int origin_z = sheets[0].origin[2], rows = sheets[0].size[2];
  auto overlaps = [](const Span& a, const Span& b) {
    return std::max(a.r0, b.r0) < std::min(a.r1, b.r1);
  };
  std::vector<Piece> done, open;
  for (int row = 0; row <= rows; ++row) {
    const std::vector<Span> spans =
        row < rows ? CalcRowSpans(sheets, row, e, elementary, margin, table) : std::vector<Span>{};
    std::vector<int> matches(spans.size(), 0);
    for (const Piece& p : open) {
      for (size_t s = 0; s < spans.size(); ++s) matches[s] += overlaps(p.spans.back(), spans[s]);
    }
    std::vector<bool> taken(spans.size(), false);
    std::vector<Piece> next;
    for (Piece& p : open) {
      int candidate = -1, count = 0;
      for (size_t s = 0; s < spans.size(); ++s) {
        if (overlaps(p.spans.back(), spans[s])) candidate = static_cast<int>(s), ++count;
      }
      if (count == 1 && matches[candidate] == 1) {
        Piece grown = p;
        grown.spans.push_back(spans[candidate]);
        if (FitPiece(grown, res, origin_z)) {
          taken[candidate] = true;
          next.push_back(std::move(grown));
          continue;
        }
      }
      done.push_back(std::move(p));
    }
    for (size_t s = 0; s < spans.size(); ++s) {
      if (taken[s]) continue;
      Piece p;
      p.row0 = row;
      p.spans = {spans[s]};
      FitPiece(p, res, origin_z);  // a single row always fits: a rectangle
      next.push_back(std::move(p));
    }
    open = std::move(next);
  }
  return done;
}

// ---------------------------------------------------------------------------------------------
// Cells.

// Normalizes each half-space so that its normal's computed norm is exactly 1.0 (nudging the
// largest component by an ulp or two): FromHalfSpaces then leaves it as it is, so the cells
// read back from a cache file are bit-identical to the computed ones.
ConvexRegion MakeCell(std::vector<HalfSpace> half_spaces) {
  for (HalfSpace& h : half_spaces) {
    const double norm = h.normal.norm();
    h.normal /= norm;
    h.offset /= norm;
    int largest = 0;
    h.normal.cwiseAbs().maxCoeff(&largest);
    for (int nudge = 0; nudge < 16; ++nudge) {
      const double n = h.normal.norm();
      if (n == 1.0) break;
      const double c = h.normal[largest];
      h.normal[largest] = std::nextafter(c, n > 1.0 ? 0.0 : (c > 0 ? 2.0 : -2.0));
    }
  }
  return ConvexRegion::FromHalfSpaces(half_spaces);
}

void AddCell(ConvexRegion cell, double volume, ReachableSet* set) {
  if (!(volume > 1e-12)) return;
  set->cells_Base.push_back(std::move(cell));
  set->cell_volumes_m3.push_back(volume);
  set->volume_m3 += volume;
}

// The sector [a, a + Δ] of a piece: with t = u_mid·p, inner(z) <= t <= outer(z)·cos(Δ/2)
// between the two radial planes. Every point has r in [t, t / cos(Δ/2)], so it lies in the
// piece's trapezoid turned to its azimuth: inside the reachable set, never outside.
void AddSector(const Piece& piece, double a, double delta, ReachableSet* set) {
  const Eigen::Vector3d u(std::cos(a + delta / 2), std::sin(a + delta / 2), 0);
  const double c = std::cos(delta / 2);
  std::vector<HalfSpace> h = {
      {-Eigen::Vector3d::UnitZ(), -piece.z0},
      {Eigen::Vector3d::UnitZ(), piece.z1},
      {Eigen::Vector3d(std::sin(a), -std::cos(a), 0), 0},                      // azimuth >= a
      {Eigen::Vector3d(-std::sin(a + delta), std::cos(a + delta), 0), 0},      // azimuth <= a + Δ
      {Eigen::Vector3d(-u.x(), -u.y(), piece.inner.d), -piece.inner.c},        // t >= inner(z)
      {Eigen::Vector3d(u.x(), u.y(), -c * piece.outer.d), c * piece.outer.c},  // t <= c·outer(z)
  };
  ConvexRegion cell = MakeCell(h);
  // The cross-section at height z is a trapezoid of area tan(Δ/2)·((c·outer)² − inner²),
  // quadratic in z: Simpson's rule is exact. A pinch (c·outer < inner somewhere) needs the
  // general measure.
  auto area = [&](double z) {
    const double out = c * piece.outer.at(z), in = piece.inner.at(z);
    return std::tan(delta / 2) * (out * out - in * in);
  };
  const double z_mid = 0.5 * (piece.z0 + piece.z1);
  const bool simple = c * piece.outer.at(piece.z0) >= piece.inner.at(piece.z0) &&
                      c * piece.outer.at(piece.z1) >= piece.inner.at(piece.z1);
  double volume = 0;
  if (simple) {
    volume = (piece.z1 - piece.z0) / 6 * (area(piece.z0) + 4 * area(z_mid) + area(piece.z1));
  } else if (!cell.IsEmpty() && cell.dimension() == 3) {
    volume = cell.CalcMeasure();
  }
  AddCell(std::move(cell), volume, set);
}

// Cuts a piece over one elementary arc into equal sectors of at most max_sector_rad.
void AddPieceOverArc(const Piece& piece, const Arc& arc, const ReachOptions& options,
                     ReachableSet* set) {
  const double span = arc.end - arc.begin;
  const int sectors =
      std::max(1, static_cast<int>(std::ceil(span / options.max_sector_rad - 1e-9)));
  const double delta = span / sectors;
  for (int s = 0; s < sectors; ++s) AddSector(piece, arc.begin + s * delta, delta, set);
}

}  // namespace

void MakeSectorCells(const std::vector<CellGrid>& sheets, const std::vector<double>& sheet_rad,
                     const Symmetry& symmetry, const ReachOptions& options, ReachableSet* set) {
  const std::vector<Arc> bit_arcs = CalcBitArcs(sheet_rad, symmetry);
  const std::vector<Arc> elementary = CalcElementaryArcs(bit_arcs);
  PRS_CHECK(elementary.size() <= 64);
  CoverTable table(bit_arcs, elementary);
  for (int e = 0; e < static_cast<int>(elementary.size()); ++e) {
    for (const Piece& piece : BuildPieces(sheets, e, elementary, options.margin_m, table)) {
      AddPieceOverArc(piece, elementary[e], options, set);
    }
  }
}

void MakeBoxCells(const CellGrid& grid, ReachableSet* set) {
  struct Box {
    int x0, x1, y0, y1, z0, z1;
  };
  auto emit = [&](const Box& b) {
    const double res = grid.resolution_m;
    const Eigen::Vector3d lo =
        res * Eigen::Vector3d(grid.origin[0] + b.x0, grid.origin[1] + b.y0, grid.origin[2] + b.z0);
    const Eigen::Vector3d hi =
        res * Eigen::Vector3d(grid.origin[0] + b.x1, grid.origin[1] + b.y1, grid.origin[2] + b.z1);
    std::vector<HalfSpace> h;
    for (int a = 0; a < 3; ++a) {
      h.push_back({-Eigen::Vector3d::Unit(a), -lo[a]});
      h.push_back({Eigen::Vector3d::Unit(a), hi[a]});
    }
    AddCell(MakeCell(h), (hi - lo).prod(), set);
  };
  std::vector<Box> open;  // boxes that may still grow in z
  for (int k = 0; k <= grid.size[2]; ++k) {
    std::vector<Box> layer;  // this layer's rectangles: runs along x merged along y
    for (int j = 0; k < grid.size[2] && j < grid.size[1]; ++j) {
      for (int i = 0; i < grid.size[0];) {
        if (!grid.is_in(i, j, k)) {
          ++i;
          continue;
        }
        int end = i;
        while (end < grid.size[0] && grid.is_in(end, j, k)) ++end;
        auto same = std::find_if(layer.begin(), layer.end(), [&](const Box& b) {
          return b.x0 == i && b.x1 == end && b.y1 == j;
        });
        if (same != layer.end()) {
          same->y1 = j + 1;
        } else {
          layer.push_back({i, end, j, j + 1, k, k + 1});
        }
        i = end;
      }
    }
    std::vector<Box> still_open;
    for (const Box& b : layer) {
      auto below = std::find_if(open.begin(), open.end(), [&](const Box& o) {
        return o.z1 == k && o.x0 == b.x0 && o.x1 == b.x1 && o.y0 == b.y0 && o.y1 == b.y1;
      });
      if (below != open.end()) {
        Box grown = *below;
        grown.z1 = k + 1;
        still_open.push_back(grown);
        below->z1 = -1;  // taken
      } else {
        still_open.push_back(b);
      }
    }
    for (const Box& o : open) {
      if (o.z1 == k) emit(o);  // not continued into this layer
    }
    open = std::move(still_open);
  }
  for (const Box& o : open) emit(o);
}

}  // namespace prs::kinematics::internal
