// The in-memory source manager: line tables and offset-to-line/column conversion.
#include "lang/source.h"

#include <algorithm>
#include <stdexcept>

namespace prs::lang {

SourceSpan Join(SourceSpan a, SourceSpan b) {
  return SourceSpan{a.file, std::min(a.begin, b.begin), std::max(a.end, b.end)};
}

FileId SourceManager::AddFile(std::string path, std::string text) {
  File f{std::move(path), std::move(text), {0}};
  for (uint32_t i = 0; i < f.text.size(); ++i) {
    // '\n', '\r\n' and a lone '\r' each end a line.
    if (f.text[i] == '\r' && i + 1 < f.text.size() && f.text[i + 1] == '\n') ++i;
    if (f.text[i] == '\n' || f.text[i] == '\r') f.line_starts.push_back(i + 1);
  }
  files_.push_back(std::move(f));
  return static_cast<FileId>(files_.size() - 1);
}

const SourceManager::File& SourceManager::file(FileId id) const {
  if (id >= files_.size()) {
    throw std::out_of_range("SourceManager: unknown file id " + std::to_string(id));
  }
  return files_[id];
}

const std::string& SourceManager::path(FileId id) const { return file(id).path; }

std::string_view SourceManager::text(FileId id) const { return file(id).text; }

LineColumn SourceManager::CalcLineColumn(FileId id, uint32_t offset) const {
  const File& f = file(id);
  offset = std::min<uint32_t>(offset, f.text.size());
  auto it = std::upper_bound(f.line_starts.begin(), f.line_starts.end(), offset);
  uint32_t line_index = static_cast<uint32_t>(it - f.line_starts.begin()) - 1;
  uint32_t column = 1;
  for (uint32_t i = f.line_starts[line_index]; i < offset; ++i) {
    // Count code points: skip UTF-8 continuation bytes.
    if ((static_cast<unsigned char>(f.text[i]) & 0xC0) != 0x80) ++column;
  }
  return LineColumn{line_index + 1, column};
}

uint32_t SourceManager::LineStart(FileId id, uint32_t line) const {
  const File& f = file(id);
  if (line == 0 || line > f.line_starts.size()) return static_cast<uint32_t>(f.text.size());
  return f.line_starts[line - 1];
}

std::string_view SourceManager::LineText(FileId id, uint32_t line) const {
  const File& f = file(id);
  if (line == 0 || line > f.line_starts.size()) return {};
  uint32_t begin = f.line_starts[line - 1];
  uint32_t end = begin;
  while (end < f.text.size() && f.text[end] != '\n' && f.text[end] != '\r') ++end;
  return std::string_view(f.text).substr(begin, end - begin);
}

}  // namespace prs::lang
