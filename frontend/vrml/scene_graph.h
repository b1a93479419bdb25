#pragma once
// The VRML97 scene graph as read from a file: nodes with their explicitly written fields (defaults
// come from the node's interface), DEF/USE sharing, PROTO/EXTERNPROTO definitions and ROUTEs.
// Everything needed to write the file back (frontend/vrml/writer) is kept.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "frontend/source.h"

namespace fscript::vrml {

enum class FieldType : uint8_t {
#define FS_FIELD_TYPE(N, K, MF) N,
#include "frontend/vrml/field_types.def"
};

const char* type_name(FieldType t);
bool type_from_name(const std::string& name, FieldType& out);
int numbers_per_element(FieldType t);  // 0: strings, nodes, images
bool is_multi(FieldType t);
FieldType single_of(FieldType t);  // MFVec3f -> SFVec3f

enum class Access : uint8_t { Field, ExposedField, EventIn, EventOut };
const char* access_name(Access a);

struct Node;
using NodePtr = std::shared_ptr<Node>;

// A field value. Numeric types keep every component flattened in `nums` (SFBool as 0/1, SFImage
// as width, height, components, pixels...); strings keep the span of each string's contents.
struct Value {
  FieldType type = FieldType::SFFloat;
  std::vector<double> nums;
  std::vector<std::string> strs;
  std::vector<frontend::Span> str_spans;
  std::vector<NodePtr> nodes;  // SFNode: one entry (nullptr for NULL); MFNode: the list
  frontend::Span span;

  size_t elements() const;  // MF element count (SF: 1)
};

struct FieldDecl {
  std::string name;
  FieldType type = FieldType::SFFloat;
  Access access = Access::Field;
  bool has_default = false;  // EXTERNPROTO and eventIn/eventOut declarations have none
  Value default_value;
  frontend::Span span;
  std::string doc;  // standard nodes: what the field does (the "##" lines of nodes_vrml97.wrl)
};

// A node type's interface: a standard node, an FVRML node, or a PROTO/EXTERNPROTO.
struct Interface {
  std::string name;
  std::vector<FieldDecl> fields;
  std::string doc;  // standard nodes: what the node is (the "##" lines of nodes_vrml97.wrl)
  const FieldDecl* find(const std::string& field) const;
};

struct FieldSlot {
  std::string name;
  Value value;
  std::string is_ref;  // inside a PROTO body: "IS name" (value unused)
  frontend::Span span;
};

struct ProtoDef;

struct Node {
  std::string type;                  // as written: "Transform", "FShape", "MyProto"
  const Interface* iface = nullptr;  // fields allowed and their defaults
  const ProtoDef* proto = nullptr;   // a user PROTO instance (expanded by the scene layer)
  bool fvrml = false;                // one of the six FVRML nodes
  std::string def_name;
  std::vector<FieldSlot> fields;     // as written, in order
  std::vector<FieldDecl> script_decls;  // a Script node's own interface declarations
  frontend::Span span;
  const frontend::SourceFile* file = nullptr;  // the file the node was read from (spans index it)
  std::vector<NodePtr> inlined;  // an Inline of a local file: that file's root nodes (load_inlines)

  // The explicit value of `field`, else its default from the interface (nullptr if neither).
  const Value* get(const std::string& field) const;
  const FieldSlot* slot(const std::string& field) const;
};

struct Route {
  std::string from_node, from_field, to_node, to_field;
  frontend::Span span;
};

struct ProtoDef {
  Interface iface;
  bool external = false;
  std::vector<std::string> urls;  // EXTERNPROTO
  const ProtoDef* definition = nullptr;  // EXTERNPROTO of a local file: the PROTO read (load_inlines)
  std::vector<NodePtr> body;      // PROTO
  std::vector<Route> routes;
  frontend::Span span;
};

// An Inline none of whose URLs was read: a local file missing or unreadable, or only remote URLs
// (never fetched). The scene is drawn without it (load_inlines).
struct MissingInline {
  std::string url;        // the first URL
  std::string looked_at;  // the paths and URLs tried, in order, comma-separated
  std::string reason;     // why the last one failed
  const frontend::SourceFile* file = nullptr;
  frontend::Span span;  // the URL in `file`
};

struct Scene {
  std::unique_ptr<frontend::SourceFile> file;
  std::vector<NodePtr> roots;
  std::vector<Route> routes;
  std::vector<std::unique_ptr<ProtoDef>> protos;
  std::map<std::string, NodePtr> defs;  // last DEF of each name at the top level
  std::vector<std::unique_ptr<Scene>> inlines;  // the local files Inlines and EXTERNPROTOs pulled in (load_inlines)
  std::vector<MissingInline> missing_inlines;    // this file's and its Inlines' (load_inlines)

  // Top-level statements in file order, for the writer: (kind, index into roots/protos/routes).
  enum class Kind : uint8_t { Node, Proto, Route };
  std::vector<std::pair<Kind, size_t>> order;
};

// The file a node was read from: an Inline's (vrml::load_inlines), else the scene's.
inline const frontend::SourceFile& file_of(const Scene& scene, const Node& n) { return n.file ? *n.file : *scene.file; }

// The standard node interfaces (VRML97 and FVRML), parsed once from nodes_vrml97.wrl.
const Interface* standard_interface(const std::string& node_type);
// A declaration as the standard writes it: "exposedField SFVec3f bboxSize 10 10 10".
std::string declaration_text(const FieldDecl& f);
std::vector<std::string> standard_node_types();  // sorted
bool is_fvrml_node(const std::string& node_type);

}  // namespace fscript::vrml
