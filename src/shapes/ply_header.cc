// The PLY header check (ply_header.h), by the grammar of the format's header: every line is
// `format`, `comment`, `obj_info`, `element NAME COUNT`, `property TYPE NAME` or
// `property list COUNT_TYPE ITEM_TYPE NAME`, up to `end_header`.
#include "shapes/ply_header.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <sstream>
#include <vector>

namespace prs::shapes::internal {
namespace {

constexpr size_t kMaxHeaderBytes = 64 * 1024;

bool IsScalarType(const std::string& type) {
  static const std::array<const char*, 16> kTypes = {
      "char", "uchar", "short", "ushort", "int", "uint", "float", "double",
      "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  return std::any_of(kTypes.begin(), kTypes.end(), [&](const char* t) { return type == t; });
}

std::vector<std::string> SplitWords(std::string_view line) {
  std::vector<std::string> words;
  std::istringstream stream{std::string(line)};
  for (std::string word; stream >> word;) words.push_back(word);
  return words;
}

std::string AtLine(int line, const std::string& what) {
  return "has a malformed PLY header: line " + std::to_string(line) + " " + what;
}

}  // namespace

std::optional<std::string> CheckPlyHeader(std::string_view bytes) {
  // The line "end_header" itself (a word ending in it, "verteend_header", is not the end:
  // assimp then reads on looking for it, forever).
  size_t end = std::string_view::npos;
  for (size_t at = bytes.find("\nend_header"); at != std::string_view::npos && at < kMaxHeaderBytes;
       at = bytes.find("\nend_header", at + 1)) {
    const size_t after = at + 11;
    if (after == bytes.size() || bytes[after] == '\n' || bytes[after] == '\r') {
      end = at + 1;
      break;
    }
  }
  if (end == std::string_view::npos)
    return "has no PLY header (no end_header line in its first 64 KB)";
  const std::string_view header = bytes.substr(0, end);
  const size_t body_bytes = bytes.size() - end;
  bool has_format = false, has_element = false;
  uint64_t total_count = 0;
  int number = 0;
  for (size_t begin = 0; begin < header.size();) {
    size_t stop = header.find('\n', begin);
    if (stop == std::string_view::npos) stop = header.size();
    const std::vector<std::string> words = SplitWords(header.substr(begin, stop - begin));
    begin = stop + 1;
    ++number;
    if (number == 1) {
      if (words.size() != 1 || words[0] != "ply") return std::string("does not start with \"ply\"");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "format") {
      if (words.size() != 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" &&
                                words[1] != "binary_big_endian"))
        return AtLine(number, "is not \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
      has_format = true;
    } else if (words[0] == "element") {
      uint64_t count = 0;
      const std::string& text = words.size() == 3 ? words[2] : std::string();
      const auto [ptr, error] = std::from_chars(text.data(), text.data() + text.size(), count);
      if (words.size() != 3 || error != std::errc() || ptr != text.data() + text.size())
        return AtLine(number, "is not \"element NAME COUNT\"");
      total_count += count;
      // Every element takes at least one byte of the body: a larger count is a truncated file
      // (and would have the reader reserve memory for elements that are not there).
      if (total_count > body_bytes) return AtLine(number, "counts more elements than the file holds");
      has_element = true;
    } else if (words[0] == "property") {
      if (!has_element) return AtLine(number, "has a property before any element");
      const bool list = words.size() == 5 && words[1] == "list" && IsScalarType(words[2]) &&
                        IsScalarType(words[3]);
      const bool scalar = words.size() == 3 && IsScalarType(words[1]);
      if (!list && !scalar)
        return AtLine(number, "is not \"property TYPE NAME\" or \"property list TYPE TYPE NAME\"");
    } else {
      return AtLine(number, "is not a format, element, property or comment line");
    }
  }
  if (!has_format) return std::string("has a PLY header without a format line");
  return std::nullopt;
}

}  // namespace prs::shapes::internal
