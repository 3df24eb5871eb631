// Aligned plain-text tables for the reports of `prs check` and `prs stats`: columns padded to
// their widest cell (counting UTF-8 code points, so "∩" is one column), numbers right-aligned.
#pragma once

#include <string>
#include <vector>

namespace prs::cli {

class TextTable {
 public:
  /// `alignment` has one letter per column, 'l' or 'r'; missing letters mean 'l'.
  TextTable(std::vector<std::string> header, std::string alignment = "");

  /// Adds a row; missing cells are empty, extra cells are ignored.
  void AddRow(std::vector<std::string> cells);
  bool empty() const { return rows_.empty(); }

  /// The header and the rows, each line indented by `indent` spaces, columns two spaces
  /// apart, trailing spaces trimmed, every line ending with a newline.
  std::string Format(int indent = 2) const;

 private:
  std::vector<std::string> header_;
  std::string alignment_;
  std::vector<std::vector<std::string>> rows_;
};

/// The number of terminal columns `text` takes: its UTF-8 code points.
size_t CalcDisplayWidth(const std::string& text);

}  // namespace prs::cli
