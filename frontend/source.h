#pragma once
// Source files, positions and spans: the one notion of "where" shared by every diagnostic.
// A SourceFile may be a slice of a larger file (a script inside a .wrl): it maps offsets back.
#include <cstdint>
#include <string>
#include <vector>

namespace fscript::frontend {

// A half-open byte range [begin, end) in one SourceFile's text.
struct Span {
  uint32_t begin = 0;
  uint32_t end = 0;
};

// Line and column, both 1-based; column counts bytes.
struct LineCol {
  uint32_t line = 1;
  uint32_t col = 1;
};

// The text of a script plus where it sits in its file. For a script embedded in a .wrl file,
// `text` is the string's contents and (base_line, base_col) the position of its first byte.
class SourceFile {
 public:
  SourceFile(std::string path, std::string text, uint32_t base_line = 1, uint32_t base_col = 1);

  const std::string& path() const { return path_; }
  const std::string& text() const { return text_; }
  // Position in the enclosing file of the byte at `offset` of the text.
  LineCol position(uint32_t offset) const;
  // Full line of the enclosing file that holds `offset` (the caret line of a diagnostic).
  std::string line_text(uint32_t offset) const;
  // Line `line` (1-based, in the enclosing file's numbering), or "" when it is not known.
  std::string line_at(uint32_t line) const;
  // Replaces the line used for carets when the text is a slice (the .wrl's own lines).
  void set_outer_lines(std::vector<std::string> lines) { outer_lines_ = std::move(lines); }

 private:
  std::string path_;
  std::string text_;
  uint32_t base_line_;
  uint32_t base_col_;
  std::vector<uint32_t> line_starts_;
  std::vector<std::string> outer_lines_;
};

}  // namespace fscript::frontend
