// The bytes a MuJoCo 2.2 render context is made from: what mjr_makeContext reads of the model
// (the offscreen, shadow, material, texture, plane, mesh, height-field and skin parts, and the
// parameters it copies from mjVisual and the extent).
#include "render/context_key.h"

#include <cstddef>

namespace prs::render {
namespace {

// Appends the count, then the values: arrays of different lengths never run together.
template <typename T>
void AppendArray(const T* values, int count, std::string& key) {
  key.append(reinterpret_cast<const char*>(&count), sizeof count);
  if (count > 0) {
    key.append(reinterpret_cast<const char*>(values), static_cast<size_t>(count) * sizeof(T));
  }
}

}  // namespace

std::string CalcRenderContextKey(const mjModel& m) {
  if (m.nskin > 0) return {};
  std::string key;
  AppendArray(&m.vis, 1, key);          // buffer sizes, quality, fog, line width
  AppendArray(&m.stat.extent, 1, key);  // infinite planes, fog and the shadow clip scale with it
  AppendArray(m.tex_type, m.ntex, key);
  AppendArray(m.tex_height, m.ntex, key);
  AppendArray(m.tex_width, m.ntex, key);
  AppendArray(m.tex_adr, m.ntex, key);
  AppendArray(m.tex_rgb, m.ntexdata, key);
  AppendArray(m.mat_texid, m.nmat, key);
  AppendArray(m.mat_texuniform, m.nmat, key);
  AppendArray(m.mat_texrepeat, 2 * m.nmat, key);
  for (int i = 0; i < m.ngeom; ++i) {  // each plane geom is a display list of its own size
    if (m.geom_type[i] != mjGEOM_PLANE) continue;
    AppendArray(&i, 1, key);
    AppendArray(m.geom_size + 3 * i, 3, key);
    AppendArray(m.geom_matid + i, 1, key);
  }
  AppendArray(m.mesh_vertadr, m.nmesh, key);
  AppendArray(m.mesh_vertnum, m.nmesh, key);
  AppendArray(m.mesh_texcoordadr, m.nmesh, key);
  AppendArray(m.mesh_faceadr, m.nmesh, key);
  AppendArray(m.mesh_facenum, m.nmesh, key);
  AppendArray(m.mesh_graphadr, m.nmesh, key);
  AppendArray(m.mesh_vert, 3 * m.nmeshvert, key);
  AppendArray(m.mesh_normal, 3 * m.nmeshvert, key);
  AppendArray(m.mesh_texcoord, 2 * m.nmeshtexvert, key);
  AppendArray(m.mesh_face, 3 * m.nmeshface, key);
  AppendArray(m.mesh_graph, m.nmeshgraph, key);
  AppendArray(m.hfield_size, 4 * m.nhfield, key);
  AppendArray(m.hfield_nrow, m.nhfield, key);
  AppendArray(m.hfield_ncol, m.nhfield, key);
  AppendArray(m.hfield_adr, m.nhfield, key);
  AppendArray(m.hfield_data, m.nhfielddata, key);
  return key;
}

}  // namespace prs::render
