#pragma once
// The `fscript.preview` command (workspace/executeCommand): starts `fvrml-run SCENE --serve` for a
// document and answers with the page's URL; one preview per document, stopped with the server.
#include <map>
#include <string>

#include <nlohmann/json.hpp>

namespace fscript::lsp {

class Previews {
 public:
  Previews() = default;
  Previews(const Previews&) = delete;
  Previews& operator=(const Previews&) = delete;
  ~Previews();  // stops every preview (SIGINT, as Ctrl-C)
  // {"url": ...} for the document at `uri` (a file: URI of a .wrl or .fs), or an error result
  // ({"__error", code}, {"message", ...}) when it cannot start.
  nlohmann::json start(const std::string& uri);

 private:
  struct Running {
    int pid;
    std::string url;
  };
  std::map<std::string, Running> running_;  // by file path
};

// The path of a file: URI (percent-decoded), or "" for any other URI.
std::string path_of_uri(const std::string& uri);

}  // namespace fscript::lsp
