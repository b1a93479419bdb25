#pragma once
// FScript texts embedded in .wrl files: a script with its position in the .wrl, the FVRML fields
// that hold FScript, and the splitting of FTransform's affine fields into components.
#include <string>
#include <vector>

namespace fscript::frontend {

struct EmbeddedScript {
  std::string field;   // e.g. "definition"
  std::string text;    // the string's contents, escapes resolved
  uint32_t line = 1;   // position in the .wrl of the first character of the contents
  uint32_t col = 1;
};

// The FVRML fields whose SFString values are FScript (the plug-in's PROTO file), by node type.
bool is_fscript_field(const std::string& node_type, const std::string& field);

// The affine fields of FTransform (translation, scale, center, rotation, scaleOrientation) hold
// several expressions: separated by commas ("0.5*t, 0, 0"), or by white space when each is a
// single token ("1 0 0"). Returns the components with their own positions.
bool is_affine_field(const std::string& name);
std::vector<EmbeddedScript> split_components(const EmbeddedScript& e);

// The lines of a file, for carets under positions inside embedded strings.
std::vector<std::string> split_lines(const std::string& text);

}  // namespace fscript::frontend
