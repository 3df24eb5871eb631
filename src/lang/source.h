// Source files held in memory, and byte-offset spans into them. Reading from disk is
// the driver's job; the source manager only stores text it is given.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace prs::lang {

using FileId = uint32_t;

/// A half-open byte range [begin, end) in one file.
struct SourceSpan {
  FileId file = 0;
  uint32_t begin = 0;
  uint32_t end = 0;
};

/// Returns the smallest span covering both a and b (which must be in the same file).
SourceSpan Join(SourceSpan a, SourceSpan b);

/// A 1-based line and column; columns count UTF-8 code points.
struct LineColumn {
  uint32_t line = 1;
  uint32_t column = 1;
};

class SourceManager {
 public:
  /// Stores a file's text and returns its id (ids are dense, starting at 0).
  FileId AddFile(std::string path, std::string text);

  /// The path the file was added with. Precondition: `file` came from AddFile.
  const std::string& path(FileId file) const;
  std::string_view text(FileId file) const;
  size_t file_count() const { return files_.size(); }

  /// Returns the line and column of a byte offset (offsets past the end clamp to the end).
  LineColumn CalcLineColumn(FileId file, uint32_t offset) const;
  /// Returns the text of a 1-based line without its line terminator ("" if out of range).
  std::string_view LineText(FileId file, uint32_t line) const;
  /// Returns the byte offset where a 1-based line starts.
  uint32_t LineStart(FileId file, uint32_t line) const;

 private:
  struct File {
    std::string path;
    std::string text;
    std::vector<uint32_t> line_starts;  // byte offset of each line's first character
  };
  const File& file(FileId id) const;
  std::deque<File> files_;  // a deque: text views stay valid as files are added
};

}  // namespace prs::lang
