// Column widths and padding for TextTable.
#include "cli/text_table.h"

#include <algorithm>

namespace prs::cli {

size_t CalcDisplayWidth(const std::string& text) {
  // Count every byte that does not continue a UTF-8 sequence (continuations are 10xxxxxx).
  return static_cast<size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

TextTable::TextTable(std::vector<std::string> header, std::string alignment)
    : header_(std::move(header)), alignment_(std::move(alignment)) {
  alignment_.resize(header_.size(), 'l');
}

void TextTable::AddRow(std::vector<std::string> cells) {
  cells.resize(header_.size());
  rows_.push_back(std::move(cells));
}

std::string TextTable::Format(int indent) const {
  std::vector<size_t> widths(header_.size(), 0);
  auto measure = [&](const std::vector<std::string>& row) {
    for (size_t c = 0; c < row.size(); ++c)
      widths[c] = std::max(widths[c], CalcDisplayWidth(row[c]));
  };
  measure(header_);
  for (const auto& row : rows_) measure(row);
  auto format_row = [&](const std::vector<std::string>& row) {
    std::string line(static_cast<size_t>(indent), ' ');
    for (size_t c = 0; c < row.size(); ++c) {
      const std::string padding(widths[c] - CalcDisplayWidth(row[c]), ' ');
      if (c > 0) line += "  ";
      line += alignment_[c] == 'r' ? padding + row[c] : row[c] + padding;
    }
    line.erase(line.find_last_not_of(' ') + 1);
    return line + "\n";
  };
  std::string text = format_row(header_);
  for (const auto& row : rows_) text += format_row(row);
  return text;
}

}  // namespace prs::cli
