// Internal to prs_shapes: a check of a PLY file's header before assimp reads it. assimp 5.2's
// PLY reader loops forever on some malformed headers (found by prs_mesh_fuzz: a header cut off
// inside a property line, with no end_header), so the header is checked first, by the PLY
// format's own grammar, and refused in our words.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace prs::shapes::internal {

/// Null when `bytes` start with a well-formed PLY header ("ply", one format line, element and
/// property lines, comments, "end_header") whose element counts fit in the file; otherwise a
/// clause saying what is wrong, for "the mesh file 'F' <clause>".
std::optional<std::string> CheckPlyHeader(std::string_view bytes);

}  // namespace prs::shapes::internal
