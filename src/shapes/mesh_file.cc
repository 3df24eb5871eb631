// Meshes named by scenes files (mesh_file.h): read from their recorded path, once per process.
#include "shapes/mesh_file.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

namespace prs::shapes {

std::shared_ptr<const MeshShape> LoadRecordedMesh(const std::string& name, const std::string& path,
                                                  std::string& problem) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const MeshShape>> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = loaded.find(path); it != loaded.end()) return it->second;
  std::error_code error;
  const std::string extension = std::filesystem::path(path).extension().string();
  const bool usable = IsSupportedMeshExtension(extension.empty() ? "" : extension.substr(1)) &&
                      std::filesystem::is_regular_file(path, error) &&
                      std::filesystem::file_size(path, error) < (uint64_t(1) << 28);
  problem = "is not a mesh file that can be read here";
  if (!usable) return nullptr;
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  try {
    return loaded[path] = LoadMeshShape(bytes.str(), name, path);
  } catch (const MeshError& e) {
    problem = e.what();
    return nullptr;
  }
}

}  // namespace prs::shapes
