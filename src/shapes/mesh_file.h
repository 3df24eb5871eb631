// Meshes named by a scenes file: a scene line records a mesh shape as {"mesh": NAME, "path":
// PATH, "scale": S} (spec §8), and tools that read scenes files back (exports, pictures, the
// viewer) re-read the mesh from PATH. Kept apart from mesh.h, which the language includes
// everywhere.
#pragma once

#include <memory>
#include <string>

#include "shapes/mesh.h"

namespace prs::shapes {

/// The mesh at `path` (named `name` in messages), read once per process and then shared: a
/// regular file under 256 MB in a format LoadMeshShape reads. Null when it cannot be used, with
/// `problem` saying why as a clause ("is not a mesh file that can be read here", or the
/// loader's message). Thread-safe.
std::shared_ptr<const MeshShape> LoadRecordedMesh(const std::string& name, const std::string& path,
                                                  std::string& problem);

}  // namespace prs::shapes
