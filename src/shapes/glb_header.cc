// The GLB header check (glb_header.h), by the layout of the glTF 1.0 and 2.0 binary formats:
// little-endian 32-bit words, a header with the magic, the version and the total length, then
// chunks (2.0: length, type, data padded to 4 bytes; 1.0: one scene of a declared length).
#include "shapes/glb_header.h"

#include <cstdint>
#include <cstring>

namespace prs::shapes::internal {
namespace {

uint32_t ReadWord(std::string_view bytes, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

std::string Describe(const std::string& what) {
  return "is not a complete binary glTF file: " + what +
         "; export it again, or use .gltf with its buffers embedded";
}

}  // namespace

std::optional<std::string> CheckGlbHeader(std::string_view bytes) {
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) return std::nullopt;
  if (bytes.size() < 12) return Describe("its header is cut off");
  const uint32_t version = ReadWord(bytes, 4);
  const uint64_t length = ReadWord(bytes, 8);
  if (version != 1 && version != 2) {
    return Describe("its header names version " + std::to_string(version) + ", not 1 or 2");
  }
  if (length > bytes.size()) {
    return Describe("its header declares " + std::to_string(length) + " bytes, the file has " +
                    std::to_string(bytes.size()));
  }
  if (version == 1) {
    if (length < 20) return Describe("its header is cut off");
    const uint64_t scene = ReadWord(bytes, 12);
    if (20 + scene > length) {
      return Describe("its scene of " + std::to_string(scene) + " bytes runs past the file's end");
    }
    return std::nullopt;
  }
  for (uint64_t at = 12; at < length;) {
    if (at + 8 > length) return Describe("a chunk's header is cut off");
    const uint64_t chunk = ReadWord(bytes, size_t(at));
    if (at + 8 + chunk > length) {
      return Describe("a chunk of " + std::to_string(chunk) + " bytes at byte " +
                      std::to_string(at) + " runs past the file's end");
    }
    at += 8 + chunk;
  }
  return std::nullopt;
}

}  // namespace prs::shapes::internal
