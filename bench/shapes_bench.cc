// Mesh shapes: one collision test between two placed meshes (FCL, bounding-volume hierarchies),
// loading a mesh file, cutting it into convex pieces for MJCF (HACD), and built-in shapes'
// polytopes. Run:
// ./build/bench/shapes_bench
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shapes/collide.h"
#include "shapes/decompose.h"
#include "shapes/mesh.h"
#include "shapes/primitive.h"

namespace {

std::string ReadAsset(const std::string& name) {
  std::ifstream in(std::string(PRS_DEFAULT_SOURCE_DIR) + "/examples/assets/" + name, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// One collision test per iteration: `a` at each of `poses` in turn against `b` at the origin.
// Returns how many overlapped.
int64_t TimeCollisions(benchmark::State& state, const prs::shapes::Collider& a,
                       const std::vector<Eigen::Isometry3d>& poses, const prs::shapes::Collider& b) {
  int64_t hits = 0;
  size_t k = 0;
  for (auto _ : state) {
    hits += prs::shapes::DoCollidersOverlap(a, poses[k++ % poses.size()], b,
                                            Eigen::Isometry3d::Identity());
  }
  return hits;
}

// The mug (~1,100 triangles) against the bowl (~5,000), at poses from near misses to contact:
// the cost the sampler pays when two meshes' bounding boxes overlap.
void BM_MeshPairCollision(benchmark::State& state) {
  const auto mug = prs::shapes::LoadMeshShape(ReadAsset("mug.obj"), "mug.obj", "mug.obj");
  const auto bowl = prs::shapes::LoadMeshShape(ReadAsset("bowl.obj"), "bowl.obj", "bowl.obj");
  const auto a = prs::shapes::Collider::MakeMesh(*mug, 1, 1e-6);
  const auto b = prs::shapes::Collider::MakeMesh(*bowl, 1, 1e-6);
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < 64; ++k) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    X.translation() = Eigen::Vector3d(0.06 + 0.01 * (k % 16), 0.002 * (k % 5), 0.0);
    poses.push_back(X);
  }
  const int64_t hits = TimeCollisions(state, *a, poses, *b);
  state.counters["triangles_a"] = static_cast<double>(mug->mesh.triangles.size());
  state.counters["triangles_b"] = static_cast<double>(bowl->mesh.triangles.size());
  state.counters["overlap_fraction"] = static_cast<double>(hits) / state.iterations();
}
BENCHMARK(BM_MeshPairCollision);

void BM_LoadBowlMesh(benchmark::State& state) {
  const std::string bytes = ReadAsset("bowl.obj");
  for (auto _ : state) benchmark::DoNotOptimize(prs::shapes::LoadMeshShape(bytes, "bowl.obj", "bowl.obj"));
}
BENCHMARK(BM_LoadBowlMesh)->Unit(benchmark::kMillisecond);

void BM_BuildBowlCollider(benchmark::State& state) {
  const auto bowl = prs::shapes::LoadMeshShape(ReadAsset("bowl.obj"), "bowl.obj", "bowl.obj");
  for (auto _ : state) benchmark::DoNotOptimize(prs::shapes::Collider::MakeMesh(*bowl, 1, 1e-6));
}
BENCHMARK(BM_BuildBowlCollider)->Unit(benchmark::kMillisecond);

// The convex pieces MJCF export (and the simulator's world) uses, computed once per mesh per
// process. The result is cached by content, so each iteration loads a copy moved by a
// different tiny offset to measure the computation itself.
void BM_ConvexPieces(benchmark::State& state, const char* name) {
  const auto mesh = prs::shapes::LoadMeshShape(ReadAsset(name), name, name);
  size_t pieces = 0;
  int k = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto copy = std::make_shared<prs::shapes::MeshShape>(*mesh);
    copy->mesh.vertices_O[0].x() += 1e-12 * ++k;
    state.ResumeTiming();
    pieces = prs::shapes::CalcConvexPieces(*copy)->size();
  }
  state.counters["triangles"] = static_cast<double>(mesh->mesh.triangles.size());
  state.counters["pieces"] = static_cast<double>(pieces);
}
BENCHMARK_CAPTURE(BM_ConvexPieces, bowl, "bowl.obj")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_ConvexPieces, mug, "mug.obj")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_ConvexPieces, shelf, "shelf.obj")->Unit(benchmark::kMillisecond)->Iterations(3);

// A built-in shape's polytope (shapes/primitive.h): what a scene pays when the shape's size is
// drawn anew (sizes repeated are cached per thread).
void BM_MakePrimitive(benchmark::State& state, prs::shapes::Primitive kind) {
  size_t vertices = 0;
  int k = 0;
  for (auto _ : state) {
    const Eigen::Vector3d size(0.06 + 1e-6 * (++k % 1000), 0.07, 0.12);
    vertices = prs::shapes::MakePrimitiveShape(kind, size)->mesh.vertices_O.size();
  }
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK_CAPTURE(BM_MakePrimitive, cylinder, prs::shapes::Primitive::kCylinder)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MakePrimitive, sphere, prs::shapes::Primitive::kSphere)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_MakePrimitive, capsule, prs::shapes::Primitive::kCapsule)->Unit(benchmark::kMicrosecond);

// Two 0.1 m balls (their polytopes) at poses from apart to overlapping: a primitive pair test.
void BM_SpherePairCollision(benchmark::State& state) {
  const auto ball = prs::shapes::MakePrimitiveShape(prs::shapes::Primitive::kSphere, {0.1, 0.1, 0.1});
  const auto collider = prs::shapes::Collider::MakeMesh(*ball, 1, 1e-6);
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < 64; ++k) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(0.05 + 0.001 * k, 0.05 + 0.0005 * k, 0.01 * (k % 3));
    poses.push_back(X);
  }
  const int64_t hits = TimeCollisions(state, *collider, poses, *collider);
  state.counters["triangles"] = static_cast<double>(ball->mesh.triangles.size());
  state.counters["overlap_fraction"] = static_cast<double>(hits) / state.iterations();
}
BENCHMARK(BM_SpherePairCollision);

}  // namespace

BENCHMARK_MAIN();
