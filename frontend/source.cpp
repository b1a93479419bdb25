// Source files and line maps: offset -> (line, col) by binary search over line starts.
#include "frontend/source.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace fscript::frontend {

SourceFile::SourceFile(std::string path, std::string text, uint32_t base_line, uint32_t base_col)
    : path_(std::move(path)), text_(std::move(text)), base_line_(base_line), base_col_(base_col) {
  line_starts_.push_back(0);
  for (uint32_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
}

LineCol SourceFile::position(uint32_t offset) const {
  offset = std::min<uint32_t>(offset, static_cast<uint32_t>(text_.size()));
  auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  uint32_t line_index = static_cast<uint32_t>(it - line_starts_.begin()) - 1;
  uint32_t col = offset - line_starts_[line_index] + 1;
  if (line_index == 0) col += base_col_ - 1;
  return {base_line_ + line_index, col};
}

std::string SourceFile::line_at(uint32_t line) const {
  if (!outer_lines_.empty()) return line >= 1 && line <= outer_lines_.size() ? outer_lines_[line - 1] : "";
  if (line < base_line_ || line - base_line_ >= line_starts_.size()) return "";
  return line_text(line_starts_[line - base_line_]);
}

std::string SourceFile::line_text(uint32_t offset) const {
  LineCol lc = position(offset);
  if (!outer_lines_.empty()) {
    if (lc.line >= 1 && lc.line <= outer_lines_.size()) return outer_lines_[lc.line - 1];
    return "";
  }
  offset = std::min<uint32_t>(offset, static_cast<uint32_t>(text_.size()));
  auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  uint32_t start = *(it - 1);
  uint32_t end = start;
  while (end < text_.size() && text_[end] != '\n') ++end;
  std::string line = text_.substr(start, end - start);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

}  // namespace fscript::frontend
