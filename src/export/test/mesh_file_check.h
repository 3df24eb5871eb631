// A check shared by the URDF and SDF tests: the mesh file a format names, read afresh from its
// file:// URI, scaled and moved as the file says, has its bounding box centred on the body's
// origin and the body's size.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "export/export.h"
#include "export/test/example_scenes.h"
#include "shapes/mesh.h"

namespace prs::exporting::testing_scenes {

inline void ExpectMeshFileFits(const std::string& uri, const Eigen::Vector3d& scale,
                               const Eigen::Vector3d& p_offset, const Body& body) {
  ASSERT_EQ(uri.rfind("file:///", 0), 0u) << body.name << ": " << uri;
  const std::string path = uri.substr(7);
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << body.name << ": cannot read " << path;
  std::stringstream bytes;
  bytes << in.rdbuf();
  const auto mesh = shapes::LoadMeshShape(bytes.str(), path, path);
  EXPECT_TRUE(SameVector(scale.cwiseProduct(mesh->p_FileCenter) + p_offset, Eigen::Vector3d::Zero(), 1e-12))
      << body.name;
  EXPECT_TRUE(SameVector(scale.cwiseProduct(mesh->extents), body.size, 1e-12)) << body.name;
}

}  // namespace prs::exporting::testing_scenes
