// Independently of the stability and settling stages: a scene's MJCF export loaded and stepped
// by MuJoCo directly, each body's movement checked.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "export/export.h"
#include "sim/mujoco_model.h"

namespace prs::sim::testing_scenes {

/// Steps `scene`'s MJCF for `duration_s` and expects every body to end within `max_move_m` of
/// where it started; `context` prefixes the failure messages.
inline void ExpectExportStaysPut(const exporting::ExportScene& scene, double duration_s,
                                 double max_move_m, const std::string& context) {
  const ModelPtr model = LoadModelFromXml(exporting::WriteScene(scene, exporting::Format::kMjcf));
  const DataPtr data = MakeData(*model);
  mj_forward(model.get(), data.get());
  std::vector<Eigen::Vector3d> p_start;
  for (int body = 0; body < model->nbody; ++body) p_start.emplace_back(data->xpos + 3 * body);
  while (data->time < duration_s) mj_step(model.get(), data.get());
  for (int body = 1; body < model->nbody; ++body) {
    EXPECT_LT((Eigen::Vector3d(data->xpos + 3 * body) - p_start[body]).norm(), max_move_m)
        << context << " body " << mj_id2name(model.get(), mjOBJ_BODY, body);
  }
}

}  // namespace prs::sim::testing_scenes
