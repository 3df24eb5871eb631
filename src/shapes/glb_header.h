// Internal to prs_shapes: a check of a binary glTF (GLB) file's header and chunk lengths before
// assimp reads it. assimp 5.2 allocates a chunk's declared length before checking it against the
// file (found by prs_mesh_fuzz: a 600-byte file declaring a 2 GiB JSON chunk ran the process out
// of memory), so the lengths are checked first, by the GLB layout, and refused in our words.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace prs::shapes::internal {

/// Null when `bytes` are not binary glTF (they do not start with the magic "glTF"), or when they
/// are and their header and chunks fit in the file: version 1 (a 20-byte header and one scene
/// chunk) or 2 (a 12-byte header, then chunks of a length and a type each); the total length
/// declared in the header at most the file's. Otherwise a clause saying what is wrong, for "the
/// mesh file 'F' <clause>".
std::optional<std::string> CheckGlbHeader(std::string_view bytes);

}  // namespace prs::shapes::internal
