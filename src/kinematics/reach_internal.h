// Internals of reachable sets shared by reach.cc (the outline), reach_grid.cc (the
// reachability maps), reach_cells.cc (the cells) and reach_cache.cc (the disk cache).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/reach.h"

namespace prs::kinematics::internal {

/// Bumped whenever the algorithm or the file format changes, so old cache files stop matching.
inline constexpr int kReachFormatVersion = 6;

/// The map's IK tolerances: tighter than IsReachable's, so that a cell judged reachable by its
/// nodes passes the independent check with room to spare.
inline constexpr double kMapPosition_m = 2e-4;
inline constexpr double kMapRotation_rad = 2e-3;

/// The first joint turns about the base's z axis through the base origin: turning it by δ
/// turns every tool pose by Rz(sign·δ).
struct Symmetry {
  int sign = 1;                 // +1 when joint 1's axis is the base's +z, −1 for −z
  double q_ref = 0;             // joint 1's value while the half-plane is mapped
  double lower = 0, upper = 0;  // joint 1's limits
};
std::optional<Symmetry> FindSymmetry(const Chain& chain);

/// A grid of cells (signed x, then y, then z; y has one cell for the half-plane map): which
/// cells are wholly reachable after the approach and margin filters.
struct CellGrid {
  double resolution_m = 0;
  std::array<int, 3> size{};    // cells along x, y, z
  std::array<int, 3> origin{};  // the integer coordinates of cell 0's lower corner / resolution
  std::vector<uint8_t> in;      // size[0]·size[1]·size[2], x fastest
  bool is_in(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < size[0] && j < size[1] && k < size[2] &&
           in[i + size[0] * (j + size[1] * static_cast<size_t>(k))];
  }
};

/// True when joint 1's range spans the whole circle (2π or more).
bool TurnsAllTheWay(const Symmetry& symmetry);

/// The angles ψ of the half-plane maps ("sheets") of a symmetric chain. Joint 1 turning all the
/// way round: one sheet, mapped with joint 1 free. Otherwise, mapped with joint 1 held: 0; the
/// gap of joint 1's range (2π − span), which fills the azimuths joint 1 cannot turn to; and
/// π/2, for points near the base that the arm reaches only with its elbow out sideways.
std::vector<double> CalcSheetAngles(const Symmetry& symmetry);

/// One half-plane map (symmetric chains): cells of the (x, z) plane at y = 0, x signed (x > 0
/// forward, x < 0 over the shoulder), reachable with joint 1 at q_ref (or free, when it turns
/// all the way round) and the targets turned by Rz(sign·q_ref + sheet_rad). Turning joint 1 over
/// its range then sweeps a forward cell over the azimuths sheet_rad + sign·[lower, upper] and a
/// backward one over those plus π. size[1] == 1; every sheet of a chain has the same size and
/// origin.
CellGrid ComputeHalfPlaneGrid(const Chain& chain, const Symmetry& symmetry, double sheet_rad,
                              const ReachOptions& options, ReachStats* stats);

/// Cuts the sheets' cells into convex cells of the base frame (reach_cells.cc): the circle is
/// cut at the ends of every sheet's arcs into elementary arcs; per elementary arc, the radial
/// cells whose arcs cover it (with a margin: reaching on past its ends by asin(margin/r)) are
/// grown into trapezoids in (r, z) with horizontal ends and slanted sides, each turned over the
/// arc in annular-sector cells of at most options.max_sector_rad.
void MakeSectorCells(const std::vector<CellGrid>& sheets, const std::vector<double>& sheet_rad,
                     const Symmetry& symmetry, const ReachOptions& options, ReachableSet* set);

/// Merges a 3-D grid's cubes into boxes (runs along x, then equal runs along y, then equal
/// rectangles along z).
void MakeBoxCells(const CellGrid& grid, ReachableSet* set);

/// The 3-D map (other chains): cubes of the base frame.
CellGrid ComputeVolumeGrid(const Chain& chain, const ReachOptions& options, ReachStats* stats);

/// The cache file's text for a set, and the set back from such a text: false (with `problem`
/// saying why) when the text is corrupt or was written for another key.
std::string FormatReachFile(const ReachableSet& set);
bool ParseReachFile(const std::string& text, const std::string& key, ReachableSet* set,
                    std::string* problem);

}  // namespace prs::kinematics::internal
