// The box-box guard: the pose from examples/bin_clutter.prs (seed 2, scene 0) where MuJoCo
// 2.2's box-box collider, unguarded, returns a contact 0.29 m deep for a 5 cm cube resting on
// the bin; guarded, every contact is as shallow as resting boxes' are, while a cube really
// sunk into the bin keeps its deep contacts.
#include "render/box_box_guard.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render/mujoco_model.h"

namespace prs::render {
namespace {

// The bin (0.8 x 0.6 x 0.1 m) and a yawed cube whose bottom face is at height `bottom_z`.
std::string CubeOnBin(double bottom_z) {
  return "<mujoco><worldbody>\n"
         "<geom name=\"bin\" type=\"box\" pos=\"0 0 0.05\" size=\"0.4 0.3 0.05\"/>\n"
         "<body pos=\"0.15812527082580607 -0.10538400539588755 " +
         std::to_string(bottom_z + 0.025) +
         "\" quat=\"0.94065764769941 0 0 -0.33935702412741175\">\n"
         "<freejoint/><geom name=\"cube\" type=\"box\" size=\"0.025 0.025 0.025\"/></body>\n"
         "</worldbody></mujoco>\n";
}

// The deepest contact after mj_forward, metres (0 when none penetrates).
double DeepestContact(const mjModel& m) {
  DataPtr d = MakeData(m);
  mj_forward(&m, d.get());
  double deepest = 0;
  for (int i = 0; i < d->ncon; ++i) deepest = std::fmax(deepest, -d->contact[i].dist);
  return deepest;
}

TEST(BoxBoxGuardTest, APhantomContactIsDroppedAndARealOneKept) {
  const ModelPtr resting = LoadModelFromXml(CubeOnBin(0.1));  // installs the guard
  EXPECT_LT(DeepestContact(*resting), 1e-6);
  // A cube sunk 2 cm into the bin: its four contacts are real and kept (MuJoCo 2.2 places
  // them on the mid-plane and reports 1 cm, unguarded too).
  const ModelPtr sunk = LoadModelFromXml(CubeOnBin(0.08));
  DataPtr d = MakeData(*sunk);
  mj_forward(sunk.get(), d.get());
  EXPECT_EQ(d->ncon, 4);
  EXPECT_NEAR(DeepestContact(*sunk), 0.01, 1e-6);
}

TEST(BoxBoxGuardTest, TheTestRejectsWhatTheUnguardedColliderReturns) {
  // The phantom contact MuJoCo 2.2 returns for this pose (depth and point as it reports them),
  // beside a real one.
  const ModelPtr m = LoadModelFromXml(CubeOnBin(0.1));
  DataPtr d = MakeData(*m);
  mj_forward(m.get(), d.get());
  mjContact phantom = d->contact[0];
  phantom.dist = -0.285;  // the depth MuJoCo 2.2 reports for this pose
  phantom.pos[0] = 0.290162;
  phantom.pos[1] = -0.20889;
  phantom.pos[2] = 0.1;
  EXPECT_FALSE(IsPossibleBoxBoxContact(*m, *d, phantom));
  EXPECT_TRUE(IsPossibleBoxBoxContact(*m, *d, d->contact[0]));
}

}  // namespace
}  // namespace prs::render
