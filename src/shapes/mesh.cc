// Mesh loading (assimp), checks, and convex hulls (qhull): see mesh.h.
#include "shapes/mesh.h"

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>

#include "shapes/glb_header.h"
#include "shapes/ply_header.h"
#include "shapes/qhull_session.h"

namespace prs::shapes {
namespace {

std::string LowerExtension(const std::string& name) {
  const size_t dot = name.find_last_of('.');
  const size_t slash = name.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// Vertices merged by exact position across all of the file's meshes (assimp joins them only
// within one mesh), so that shared edges are counted as shared.
class VertexPool {
 public:
  int Add(const Eigen::Vector3d& p) {
    auto [it, inserted] = index_.emplace(std::array<double, 3>{p.x(), p.y(), p.z()},
                                         static_cast<int>(vertices_.size()));
    if (inserted) vertices_.push_back(p);
    return it->second;
  }
  std::vector<Eigen::Vector3d>& vertices() { return vertices_; }

 private:
  std::map<std::array<double, 3>, int> index_;
  std::vector<Eigen::Vector3d> vertices_;
};

// assimp reads coordinates as floats. The shortest decimal that gives the same float is what the
// file most likely wrote ("0.6", not 0.6000000238418579), so that is the double we keep.
double ToDouble(float x) {
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, x);
  double value = x;
  std::from_chars(text, written.ptr, value);
  return value;
}

void CollectTriangles(const aiScene& scene, VertexPool& pool, TriangleMesh& mesh,
                      int* degenerate) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& source = *scene.mMeshes[m];
    std::vector<int> ids(source.mNumVertices);
    for (unsigned v = 0; v < source.mNumVertices; ++v) {
      const aiVector3D& p = source.mVertices[v];
      const Eigen::Vector3d point(ToDouble(p.x), ToDouble(p.y), ToDouble(p.z));
      if (!point.allFinite()) {
        throw MeshError("has a vertex whose coordinates are not finite numbers");
      }
      ids[v] = pool.Add(point);
    }
    for (unsigned f = 0; f < source.mNumFaces; ++f) {
      const aiFace& face = source.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines have no surface
      bool in_range = true;
      for (int k = 0; k < 3; ++k) in_range = in_range && face.mIndices[k] < source.mNumVertices;
      if (!in_range) throw MeshError("has a face that names a vertex it does not have");
      const Eigen::Vector3i t(ids[face.mIndices[0]], ids[face.mIndices[1]], ids[face.mIndices[2]]);
      const std::vector<Eigen::Vector3d>& p = pool.vertices();
      const double twice_area = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
      if (!(twice_area > 0)) {
        ++*degenerate;
        continue;
      }
      mesh.triangles.push_back(t);
    }
  }
}

// Each mesh's primitive types as its faces have them (1 index: point, 2: line, 3: triangle,
// more: polygon). A face without indices (assimp's PLY reader makes one from a face line it
// misreads) is refused: assimp's triangulation counts it as a triangle and asserts.
void CorrectPrimitiveTypes(aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh& mesh = *scene.mMeshes[m];
    unsigned types = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const unsigned n = mesh.mFaces[f].mNumIndices;
      if (n == 0) throw MeshError("has a face without vertices; check that the file is complete");
      types |= n == 1 ? aiPrimitiveType_POINT : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE : aiPrimitiveType_POLYGON;
    }
    mesh.mPrimitiveTypes = types;
  }
}

// "is not a number" or, for an infinite coordinate, "is not a finite number".
std::string DescribeNotFinite(double x, double y, double z) {
  return std::isnan(x) || std::isnan(y) || std::isnan(z) ? "is not a number"
                                                         : "is not a finite number";
}

// "(nan, 0, 0.5)".
std::string FormatPoint(double x, double y, double z) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", x, y, z);
  return text;
}

// The first `v` line of an OBJ text whose coordinates are not all finite: "vertex 3 (counting
// from 1, as the file's faces do), line 5: 'v nan 0 0'", with `what` set; nullopt when there is
// none. assimp's OBJ reader copies a vertex for every face corner, so its order is not the
// file's, and the file's numbering is what a user can look up.
std::optional<std::string> FindObjVertexNotFinite(std::string_view text, std::string* what) {
  int64_t vertex = 0, line_number = 0;
  for (size_t at = 0; at < text.size();) {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::string line(text.substr(at, end - at));
    at = end + 1;
    ++line_number;
    const size_t v = line.find_first_not_of(" \t");
    if (v == std::string::npos || line[v] != 'v' || v + 1 >= line.size() ||
        (line[v + 1] != ' ' && line[v + 1] != '\t')) {
      continue;
    }
    ++vertex;
    double xyz[3] = {0, 0, 0};
    const char* p = line.c_str() + v + 1;
    for (double& x : xyz) {
      char* stop = nullptr;
      x = std::strtod(p, &stop);
      if (stop == p) break;
      p = stop;
    }
    if (std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2])) continue;
    *what = DescribeNotFinite(xyz[0], xyz[1], xyz[2]);
    std::string shown = line.substr(v, 80);
    while (!shown.empty() && std::isspace(static_cast<unsigned char>(shown.back()))) {
      shown.pop_back();
    }
    return "vertex " + std::to_string(vertex) + " (counting from 1, as the file's faces do), " +
           "line " + std::to_string(line_number) + ": '" + shown + "'";
  }
  return std::nullopt;
}

// Refuses a vertex that is not a finite number, naming it, before assimp's post-processing:
// joining identical vertices merges a NaN vertex with another one, which left only
// "triangles of zero area" to report. The number is the file's own where the format has one
// that assimp keeps (OBJ's `v` lines; STL: three vertices a facet, in order), else assimp's.
void CheckVerticesAreNumbers(const aiScene& scene, std::string_view bytes,
                             const std::string& extension) {
  int64_t before = 0;  // vertices of the earlier meshes
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& p = mesh.mVertices[i];
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
      std::string what = DescribeNotFinite(p.x, p.y, p.z);
      std::optional<std::string> which;
      if (extension == "obj") which = FindObjVertexNotFinite(bytes, &what);
      if (!which) {
        const int64_t k = before + i;
        which = extension == "stl"
                    ? "vertex " + std::to_string(k + 1) + " (counting from 1: corner " +
                          std::to_string(k % 3 + 1) + " of facet " + std::to_string(k / 3 + 1) + ")"
                    : "vertex " + std::to_string(i + 1) + " of mesh " + std::to_string(m + 1) +
                          " (counting from 1, in the order assimp reads them)";
        *which += ", " + FormatPoint(p.x, p.y, p.z);
      }
      throw MeshError("has a vertex that " + what + ": " + *which);
    }
    before += mesh.mNumVertices;
  }
}

int CountOpenEdges(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> uses;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  int open = 0;
  for (const auto& [edge, count] : uses) open += count == 1;
  return open;
}

}  // namespace

bool IsSupportedMeshExtension(std::string_view extension) {
  return extension == "obj" || extension == "stl" || extension == "ply" || extension == "gltf" ||
         extension == "glb";
}

const char* SupportedMeshFormats() {
  return "OBJ, STL, PLY and glTF (.glb, or .gltf with its buffers embedded)";
}

std::shared_ptr<const MeshShape> LoadMeshShape(std::string_view bytes, const std::string& name,
                                               const std::string& path) {
  const std::string extension = LowerExtension(name);
  if (!IsSupportedMeshExtension(extension)) {
    throw MeshError("is not a mesh format ProbRobScene reads (" +
                    (extension.empty() ? std::string("no extension") : "." + extension) +
                    "); use " + SupportedMeshFormats());
  }
  if (bytes.empty()) throw MeshError("is empty");
  if (extension == "ply") {
    if (auto problem = internal::CheckPlyHeader(bytes)) throw MeshError(*problem);
  }
  // Binary glTF is recognised by its content, whatever the extension says.
  if (auto problem = internal::CheckGlbHeader(bytes)) throw MeshError(*problem);
  Assimp::Importer importer;
  // Read first with assimp's own validation only; then check the faces and make every mesh's
  // primitive types agree with them, which assimp's importers do not always do and its
  // triangulation asserts (aborts the process) on (found by prs_mesh_fuzz); then the
  // post-processing: triangulate, join vertices, apply node transforms (glTF scenes place
  // their meshes), drop lines and points.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(),
                                                     aiProcess_ValidateDataStructure,
                                                     extension.c_str());
  if (scene) {
    CheckVerticesAreNumbers(*scene, bytes, extension);
    CorrectPrimitiveTypes(*const_cast<aiScene*>(scene));  // the importer's own scene
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                         aiProcess_PreTransformVertices | aiProcess_SortByPType);
  }
  if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    throw MeshError("cannot be read as a ." + extension + " mesh; check that it is a complete " +
                    "file of that format (" + SupportedMeshFormats() + ")");
  }
  auto shape = std::make_shared<MeshShape>();
  shape->name = name;
  shape->path = path;
  VertexPool pool;
  CollectTriangles(*scene, pool, shape->mesh, &shape->degenerate_triangles);
  if (shape->mesh.triangles.empty()) {
    throw MeshError(shape->degenerate_triangles > 0
                        ? "has only triangles of zero area, so no surface"
                        : "has no triangles (an empty mesh, or only points and lines)");
  }
  // Keep only the vertices triangles use, then centre the bounding box on the origin.
  std::vector<int> renumber(pool.vertices().size(), -1);
  for (Eigen::Vector3i& t : shape->mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      int& id = renumber[t[k]];
      if (id < 0) {
        id = static_cast<int>(shape->mesh.vertices_O.size());
        shape->mesh.vertices_O.push_back(pool.vertices()[t[k]]);
      }
      t[k] = id;
    }
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Eigen::Vector3d& p : shape->mesh.vertices_O) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  shape->p_FileCenter = (lo + hi) / 2;
  shape->extents = hi - lo;
  if (!shape->extents.allFinite()) throw MeshError("is too large: its size is not a finite number");
  for (Eigen::Vector3d& p : shape->mesh.vertices_O) p -= shape->p_FileCenter;
  shape->open_edges = CountOpenEdges(shape->mesh);
  shape->hull_O = CalcConvexHullVertices(shape->mesh.vertices_O);
  shape->supports_O = CalcSupportPolygons(shape->mesh);
  return shape;
}

std::vector<Eigen::Vector3d> CalcConvexHullVertices(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 5) return points;
  // qhull refuses flat input; the vertex set itself has the same support function.
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if ((hi - lo).minCoeff() <= 1e-9 * std::max(1.0, (hi - lo).maxCoeff())) return points;
  std::vector<coordT> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Eigen::Vector3d& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  std::vector<Eigen::Vector3d> hull;
  const int status = internal::RunQhull(3, coordinates, "qhull Qt", [&](qhT* qh) {
    vertexT* vertex;
    FORALLvertices {
      const int id = qh_pointid(qh, vertex->point);
      if (id >= 0 && id < static_cast<int>(points.size())) hull.push_back(points[id]);
    }
  });
  if (status != 0 || hull.size() < 4) return points;  // nearly flat: keep every point
  return hull;
}

std::vector<std::string> DescribeMeshWarnings(const MeshShape& shape, double scale) {
  std::vector<std::string> warnings;
  if (shape.open_edges > 0) {
    warnings.push_back("is not closed (" + std::to_string(shape.open_edges) +
                       " edges belong to one triangle only): collisions use its surface and "
                       "containment its convex hull, so a gap in it can let objects pass");
  }
  if (shape.degenerate_triangles > 0) {
    warnings.push_back("has " + std::to_string(shape.degenerate_triangles) +
                       " triangles of zero area; they were dropped");
  }
  const double largest = shape.extents.maxCoeff() * scale;
  char size[96];
  std::snprintf(size, sizeof size, "%.4g m across at scale %g", largest, scale);
  if (largest > 20) {
    warnings.push_back(std::string("is ") + size +
                       "; if the file is in millimetres, use scale=0.001 (centimetres: 0.01)");
  } else if (largest < 0.002) {
    warnings.push_back(std::string("is only ") + size +
                       "; if the file is in metres and the scale meant millimetres, drop it");
  }
  return warnings;
}

}  // namespace prs::shapes
