// The guard (box_box_guard.h): MuJoCo's collision table is a public array of function pointers
// (mjCOLLISIONFUNC), so the box-box entry is wrapped rather than the collider rewritten.
#include "render/box_box_guard.h"

#include <cmath>
#include <mutex>

namespace prs::render {
namespace {

mjfCollision original_box_box = nullptr;

// Half the box's thickness along unit direction n (world frame).
double CalcHalfWidth(const mjModel& m, const mjData& d, int geom, const mjtNum* n) {
  const mjtNum* R = d.geom_xmat + 9 * geom;  // row-major: column j is the box's axis j
  const mjtNum* size = m.geom_size + 3 * geom;
  double half = 0;
  for (int j = 0; j < 3; ++j) {
    half += std::fabs(n[0] * R[j] + n[1] * R[3 + j] + n[2] * R[6 + j]) * size[j];
  }
  return half;
}

// How far point p lies outside the box (0 inside), along its worst axis.
double CalcOutside(const mjModel& m, const mjData& d, int geom, const mjtNum* p) {
  const mjtNum* R = d.geom_xmat + 9 * geom;
  const mjtNum* c = d.geom_xpos + 3 * geom;
  const mjtNum* size = m.geom_size + 3 * geom;
  double outside = 0;
  for (int j = 0; j < 3; ++j) {
    const double local = (p[0] - c[0]) * R[j] + (p[1] - c[1]) * R[3 + j] + (p[2] - c[2]) * R[6 + j];
    outside = std::fmax(outside, std::fabs(local) - size[j]);
  }
  return outside;
}

int GuardedBoxBox(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2,
                  mjtNum margin) {
  const int n = original_box_box(m, d, con, g1, g2, margin);
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    con[i].geom1 = g1;  // set by the caller after we return; the test reads them
    con[i].geom2 = g2;
    if (IsPossibleBoxBoxContact(*m, *d, con[i])) con[kept++] = con[i];
  }
  return kept;
}

}  // namespace

bool IsPossibleBoxBoxContact(const mjModel& m, const mjData& d, const mjContact& contact) {
  constexpr double kSlackM = 1e-3;
  const double depth = std::fmax(0.0, -contact.dist);
  const mjtNum* n = contact.frame;  // the normal is the frame's first row
  for (int geom : {contact.geom1, contact.geom2}) {
    if (depth > 2 * CalcHalfWidth(m, d, geom, n) + kSlackM) return false;
    if (CalcOutside(m, d, geom, contact.pos) > depth + kSlackM) return false;
  }
  return true;
}

void InstallBoxBoxGuard() {
  static std::once_flag once;
  std::call_once(once, [] {
    original_box_box = mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX];
    mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX] = GuardedBoxBox;
  });
}

}  // namespace prs::render
