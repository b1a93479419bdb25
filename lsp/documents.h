#pragma once
// Open documents and LSP positions: lines are 0-based and characters count UTF-16 code units, as
// LSP 3.17 says by default; our frontend counts bytes from 1. Edits arrive whole or as ranges.
#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace fscript::lsp {

struct Position {
  uint32_t line = 0, character = 0;
};

struct Analysis;

struct Document {
  std::string uri, text;
  int64_t version = 0;
  bool scene = false;  // a .wrl (VRML with FScript strings) rather than a .fs script
  uint64_t revision = 0;  // bumped by every change of `text`
  // A script inside a .wrl, taken as a document of its own: the .wrl line (0-based) its text
  // starts on, for what the features say in words ("defined at line N" is the file's line).
  uint32_t first_line = 0;
  // The analysis of `text` at `analysed_revision` (lsp/analysis.h), shared by the features.
  mutable std::shared_ptr<Analysis> analysis;
  mutable uint64_t analysed_revision = ~uint64_t{0};
};

// Byte offset of an LSP position (clamped into the text: a position past a line's end is its end,
// past the last line is the end of the text).
size_t offset_of(const std::string& text, Position p);
// LSP position of a byte offset.
Position position_of(const std::string& text, size_t offset);
// LSP position of a frontend line/column (1-based, bytes).
Position position_of_line_col(const std::string& text, uint32_t line, uint32_t col);

class Documents {
 public:
  Document& open(const std::string& uri, const std::string& text, int64_t version);
  Document* find(const std::string& uri);
  void close(const std::string& uri) { docs_.erase(uri); }
  // Replaces [from, to) with `text`.
  static void edit(Document& d, Position from, Position to, const std::string& text);

 private:
  std::map<std::string, Document> docs_;
};

bool is_scene_uri(const std::string& uri);

}  // namespace fscript::lsp
