// libFuzzer entry point for mesh files as `shape: Mesh("file")` has them read: the first byte
// picks the format ('s' STL, 'p' PLY, 'g' glTF, 'b' GLB, anything else OBJ), the rest is the
// file. A file that loads is also checked for warnings, tested for collision against a box and
// against itself (FCL), and cut into convex pieces (HACD) as MJCF export does. A file may be
// refused only with MeshError (a message for the user); any other exception, crash, hang, leak
// or sanitizer report is a bug (spec §9).
#include <cstddef>
#include <cstdint>
#include <string>

#include "shapes/collide.h"
#include "shapes/decompose.h"
#include "shapes/mesh.h"

namespace {

constexpr size_t kMaxInputBytes = 64 * 1024;

const char* NameFor(uint8_t selector) {
  switch (selector) {
    case 's': return "fuzz.stl";
    case 'p': return "fuzz.ply";
    case 'g': return "fuzz.gltf";
    case 'b': return "fuzz.glb";
    default: return "fuzz.obj";
  }
}

void UseMesh(const prs::shapes::MeshShape& mesh) {
  volatile size_t sink = prs::shapes::DescribeMeshWarnings(mesh, 1.0).size();
  const double size = mesh.extents.maxCoeff();
  if (!(size > 1e-6 && size < 1e6)) return;  // the language refuses such scales before this
  const double scale = 1.0 / size;
  const auto collider = prs::shapes::Collider::MakeMesh(mesh, scale, 1e-6);
  const auto box = prs::shapes::Collider::MakeBox(Eigen::Vector3d(0.2, 0.3, 0.1), 1e-6);
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translation() = Eigen::Vector3d(0.3, 0.1, 0.2);
  sink = sink + prs::shapes::DoCollidersOverlap(*collider, Eigen::Isometry3d::Identity(), *box, X_WB);
  sink = sink + prs::shapes::DoCollidersOverlap(*collider, Eigen::Isometry3d::Identity(), *collider,
                                                X_WB);
  if (mesh.mesh.triangles.size() <= 4000) sink = sink + prs::shapes::CalcConvexPieces(mesh)->size();
  (void)sink;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0 || size > kMaxInputBytes) return -1;
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    UseMesh(*prs::shapes::LoadMeshShape(bytes, NameFor(data[0]), "fuzz"));
  } catch (const prs::shapes::MeshError&) {
    // refused with a message: what a user sees after "the mesh file 'F' "
  }
  return 0;
}
