// Reading the local files of Inline nodes into the scene (frontend/vrml/inline.h).
#include "frontend/vrml/inline.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <unordered_set>

#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "runtime/support/files.h"

namespace fscript::vrml {
namespace {

namespace fs = std::filesystem;

// The scheme of a URL ("http" of "http://..."), or "" when it has none. One letter is a Windows
// drive, not a scheme.
std::string scheme_of(const std::string& url) {
  size_t colon = url.find(':');
  if (colon == std::string::npos || colon < 2) return "";
  for (size_t i = 0; i < colon; ++i)
    if (!std::isalnum(static_cast<unsigned char>(url[i])) && url[i] != '+' && url[i] != '-' && url[i] != '.') return "";
  return url.substr(0, colon);
}

// The file a local URL names, relative to `dir`: "file:" and a "#viewpoint" dropped, %XX decoded.
fs::path local_path(std::string url, const fs::path& dir) {
  if (scheme_of(url) == "file") url = url.substr(url.rfind("file://", 0) == 0 ? 7 : 5);
  if (size_t hash = url.find('#'); hash != std::string::npos) url.resize(hash);
  fs::path p(support::percent_decoded(url));
  return p.is_absolute() ? p : dir / p;
}

class Loader {
 public:
  Loader(frontend::DiagnosticSink& diag, std::vector<std::string>* files, std::vector<MissingInline>& missing,
         bool strict)
      : diag_(diag), files_(files), missing_(missing), strict_(strict) {}

  void load(Scene& scene, std::vector<std::string>& stack) {
    std::unordered_set<const Node*> seen;
    std::vector<Node*> todo;
    for (const auto& r : scene.roots) todo.push_back(r.get());
    while (!todo.empty()) {
      Node* n = todo.back();
      todo.pop_back();
      if (!n || !seen.insert(n).second) continue;
      if (n->type == "Inline") inline_node(scene, *n, stack);
      for (auto& f : n->fields)
        for (auto& child : f.value.nodes) todo.push_back(child.get());
    }
    for (auto& p : scene.protos)
      if (p->external && !is_fvrml_node(p->iface.name)) extern_proto(scene, *p, stack);
  }

 private:
  // The first URL of the Inline that reads (VRML97: the first that works); none: it is missing.
  void inline_node(Scene& scene, Node& n, std::vector<std::string>& stack) {
    const Value* url = n.get("url");
    if (!url || url->strs.empty()) return;
    const frontend::SourceFile& here = file_of(scene, n);
    MissingInline missing{url->strs[0], "", "", &here, url->str_spans.empty() ? n.span : url->str_spans[0]};
    for (size_t k = 0; k < url->strs.size(); ++k) {
      const std::string& u = url->strs[k];
      if (u.empty()) continue;
      if (!missing.looked_at.empty()) missing.looked_at += ", ";
      if (is_remote_url(u)) {
        missing.looked_at += u, missing.reason = "not fetched (no network)";
        continue;
      }
      frontend::Span at = k < url->str_spans.size() ? url->str_spans[k] : n.span;
      fs::path path = local_path(u, fs::path(here.path()).parent_path());
      missing.looked_at += path.string();
      bool unreadable = false;
      if (Scene* file = read(here, at, "Inline '" + u + "'", path, scene, stack, &missing.reason, &unreadable))
        n.inlined = file->roots;
      if (!unreadable) return;  // read, or an error reported (broken, circular)
    }
    if (missing.looked_at.empty()) return;
    report_missing(missing, std::all_of(url->strs.begin(), url->strs.end(), [](const std::string& u) {
                     return u.empty() || is_remote_url(u);
                   }));
  }

  void report_missing(const MissingInline& m, bool remote_only) {
    if (strict_)
      diag_.error(*m.file, m.span,
                  "Inline '" + m.url +
                      "': " + (remote_only ? m.reason : "cannot read " + m.looked_at + ": " + m.reason) +
                      ", and --strict makes a missing Inline an error");
    else if (!remote_only)  // the parser warned about remote ones
      diag_.warning(*m.file, m.span,
                    "Inline '" + m.url + "': cannot read " + m.looked_at + ": " + m.reason +
                        "; the scene is drawn without it (put the file there, or --strict to make this an error)");
    missing_.push_back(m);
  }

  // The first local URL of an EXTERNPROTO: its file read, and the PROTO the URL's #fragment names
  // (else the file's first) becomes the definition, its interface checked against the declaration.
  void extern_proto(Scene& scene, ProtoDef& p, std::vector<std::string>& stack) {
    const frontend::SourceFile& here = *scene.file;
    for (const std::string& url : p.urls) {
      if (is_remote_url(url) || url.empty()) continue;
      std::string what = "EXTERNPROTO " + p.iface.name + " '" + url + "'";
      size_t hash = url.find('#');
      std::string name = hash == std::string::npos ? "" : url.substr(hash + 1);
      Scene* file = read(here, p.span, what, local_path(url, fs::path(here.path()).parent_path()), scene, stack);
      if (!file) return;
      const ProtoDef* found = nullptr;
      for (const auto& q : file->protos)
        if (!q->external && (name.empty() || q->iface.name == name)) {
          found = q.get();
          break;
        }
      if (!found) {
        diag_.error(here, p.span,
                    what + ": " + (name.empty() ? "the file has no PROTO" : "the file has no PROTO " + name));
        return;
      }
      for (const FieldDecl& f : p.iface.fields) {
        const FieldDecl* d = found->iface.find(f.name);
        if (!d || d->type != f.type || d->access != f.access) {
          diag_.error(here, f.span,
                      what + ": " +
                          (d ? "field '" + f.name + "' is " + access_name(d->access) + " " + type_name(d->type) +
                                   " in the PROTO"
                             : "the PROTO has no field '" + f.name + "'"));
          return;
        }
      }
      p.definition = found;
      return;
    }
  }

  // A local file read and parsed (its own Inlines and EXTERNPROTOs too), kept in `scene`; nullptr
  // after an error reported at `at`. With `unreadable` given, a file that cannot be read is not
  // reported but sets it, with the reason in `why`.
  Scene* read(const frontend::SourceFile& here, frontend::Span at, const std::string& what, const fs::path& path,
              Scene& scene, std::vector<std::string>& stack, std::string* why = nullptr, bool* unreadable = nullptr) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(path, ec);
    std::string key = ec ? path.string() : canonical.string();
    if (std::find(stack.begin(), stack.end(), key) != stack.end()) {
      diag_.error(here, at,
                  what + " includes a file that includes it (directly or through other Inlines or EXTERNPROTOs)");
      return nullptr;
    }
    if (static_cast<int>(stack.size()) > kMaxInlineDepth) {
      diag_.error(here, at, what + ": files nested more than " + std::to_string(kMaxInlineDepth) + " deep");
      return nullptr;
    }
    std::string text, error;
    if (!read_scene_text(path.string(), text, error)) {
      // Not there, not allowed, a folder: missing. Too large, a gzip bomb: errors.
      const std::string kCannot = "cannot read the file: ";
      if (unreadable && error.rfind(kCannot, 0) == 0 && error.rfind(kCannot + "the file is", 0) != 0) {
        *unreadable = true, *why = error.substr(kCannot.size());
        return nullptr;
      }
      diag_.error(here, at, what + ": " + error);
      return nullptr;
    }
    if (files_) files_->push_back(path.string());
    auto child = std::make_unique<Scene>();
    if (!parse_scene(std::make_unique<frontend::SourceFile>(path.string(), text), diag_, *child)) return nullptr;
    stack.push_back(key);
    load(*child, stack);
    stack.pop_back();
    scene.inlines.push_back(std::move(child));
    return scene.inlines.back().get();
  }

  frontend::DiagnosticSink& diag_;
  std::vector<std::string>* files_;
  std::vector<MissingInline>& missing_;
  bool strict_;
};

}  // namespace

bool is_remote_url(const std::string& url) {
  std::string s = scheme_of(url);
  return !s.empty() && s != "file";
}

bool load_inlines(Scene& scene, frontend::DiagnosticSink& diag, std::vector<std::string>* files, bool strict) {
  size_t before = diag.error_count();
  std::error_code ec;
  fs::path self = fs::weakly_canonical(scene.file->path(), ec);
  std::vector<std::string> stack = {ec ? scene.file->path() : self.string()};
  Loader(diag, files, scene.missing_inlines, strict).load(scene, stack);
  return diag.error_count() == before;
}

}  // namespace fscript::vrml
