// A guard around MuJoCo 2.2's box-box collider, which for some boxes resting face to face
// (a yawed cube on a bin's floor) also returns a phantom contact: a point far outside the small
// box, deeper than the box is thick (upstream issue google-deepmind/mujoco#3476). The solver
// then ejects the box. Installed by LoadModelFromXml, so every model prs loads is guarded.
#pragma once

#include <mujoco/mujoco.h>

namespace prs::render {

/// Replaces MuJoCo's box-box collision function, once per process, with one that calls it and
/// drops each contact that no pair of touching boxes can have: deeper than either box is thick
/// along the contact normal, or with its point farther outside either box than its depth.
void InstallBoxBoxGuard();

/// Whether a box-box contact is one that two real boxes can have (the test the guard applies).
bool IsPossibleBoxBoxContact(const mjModel& m, const mjData& d, const mjContact& contact);

}  // namespace prs::render
