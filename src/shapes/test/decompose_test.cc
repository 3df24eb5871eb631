// Tests of convex pieces: convex parts kept whole and exact, a non-convex part split so that
// its notch stays free, every vertex covered, flat parts dropped, one computation per mesh.
#include <gtest/gtest.h>

#include "shapes/decompose.h"
#include "shapes/test/test_meshes.h"

namespace prs::shapes {
namespace {

// Whether `p` lies strictly inside the convex hull of `points`: adding it adds no hull vertex.
bool IsInsideHull(const Eigen::Vector3d& p, std::vector<Eigen::Vector3d> points) {
  points.push_back(p);
  for (const Eigen::Vector3d& v : CalcConvexHullVertices(points)) {
    if (v == p) return false;
  }
  return true;
}

// An L-shaped prism, height 1: the square [0, 2] x [0, 2] without its quarter [1, 2] x [1, 2].
// One closed connected surface that is not convex.
std::string LPrismObj() {
  const std::vector<Eigen::Vector2d> outline{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  std::vector<Eigen::Vector3d> v;
  for (double z : {0.0, 1.0})
    for (const Eigen::Vector2d& q : outline) v.emplace_back(q.x(), q.y(), z);
  std::vector<Eigen::Vector3i> t;
  const int n = 6;
  for (int i = 0; i < n; ++i) {  // sides
    const int j = (i + 1) % n;
    t.emplace_back(i, j, n + j);
    t.emplace_back(i, n + j, n + i);
  }
  // Caps: the L as four triangles fanned from the corner (0, 0) and (1, 1).
  const int cap[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  for (const auto& c : cap) {
    t.emplace_back(c[0], c[2], c[1]);
    t.emplace_back(n + c[0], n + c[1], n + c[2]);
  }
  return testing::FormatObj(v, t);
}

TEST(DecomposeTest, ConvexPartsAreKeptWholeAndExact) {
  const auto ring = LoadMeshShape(testing::RingObj(0.2, 0.04, 0.05), "ring.obj", "ring.obj");
  const auto pieces = CalcConvexPieces(*ring);
  ASSERT_EQ(pieces->size(), 4u);  // four bars, each a box
  for (const ConvexPiece& piece : *pieces) EXPECT_EQ(piece.points_O.size(), 8u);
  // The hole's centre is in none of them.
  for (const ConvexPiece& piece : *pieces)
    EXPECT_FALSE(IsInsideHull(Eigen::Vector3d::Zero(), piece.points_O));
}

TEST(DecomposeTest, ANonConvexPartIsSplitAndItsNotchStaysFree) {
  const auto l = LoadMeshShape(LPrismObj(), "l.obj", "l.obj");
  ASSERT_EQ(SplitConnectedParts(l->mesh).size(), 1u);
  ASSERT_FALSE(IsConvexSurface(l->mesh.vertices_O, l->mesh.triangles, 1e-9));
  const auto pieces = CalcConvexPieces(*l);
  ASSERT_GE(pieces->size(), 2u);
  // The frame is centred on the bounding box: the notch [1, 2] x [1, 2] is at [0, 1] x [0, 1].
  const Eigen::Vector3d notch_centre(0.5, 0.5, 0);
  const Eigen::Vector3d solid_centres[2] = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}};
  for (const ConvexPiece& piece : *pieces) EXPECT_FALSE(IsInsideHull(notch_centre, piece.points_O));
  for (const Eigen::Vector3d& c : solid_centres) {
    bool covered = false;
    for (const ConvexPiece& piece : *pieces) covered = covered || IsInsideHull(c, piece.points_O);
    EXPECT_TRUE(covered) << c.transpose();
  }
  // Every vertex of the mesh is a point of some piece.
  for (const Eigen::Vector3d& v : l->mesh.vertices_O) {
    bool found = false;
    for (const ConvexPiece& piece : *pieces)
      for (const Eigen::Vector3d& p : piece.points_O) found = found || (p - v).norm() < 1e-9;
    EXPECT_TRUE(found) << v.transpose();
  }
}

TEST(DecomposeTest, FlatPartsGiveNoPieceAndTheResultIsShared) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> t;
  testing::AppendBox({0, 0, 0}, {1, 1, 1}, v, t);
  const int b = static_cast<int>(v.size());  // a lone triangle beside the box
  v.insert(v.end(), {{2, 0, 0}, {3, 0, 0}, {2, 1, 0}});
  t.emplace_back(b, b + 1, b + 2);
  const auto shape = LoadMeshShape(testing::FormatObj(v, t), "box.obj", "box.obj");
  EXPECT_EQ(SplitConnectedParts(shape->mesh).size(), 2u);
  const auto pieces = CalcConvexPieces(*shape);
  ASSERT_EQ(pieces->size(), 1u);
  EXPECT_EQ(pieces->front().points_O.size(), 8u);
  // The same content (here: loaded again under another name) is not decomposed again.
  const auto again = LoadMeshShape(testing::FormatObj(v, t), "other.obj", "other.obj");
  EXPECT_EQ(CalcConvexPieces(*again).get(), pieces.get());
}

}  // namespace
}  // namespace prs::shapes
