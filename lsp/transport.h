#pragma once
// LSP base protocol over byte streams: messages framed by a `Content-Length` header. Reading never
// trusts the input: bad headers are reported and skipped, a truncated stream ends the session.
#include <iosfwd>
#include <string>

namespace fscript::lsp {

enum class ReadStatus {
  Message,    // `body` holds one message
  End,        // the stream ended (possibly in the middle of a message)
  BadHeader,  // a header block without a usable Content-Length; `error` says why
};

constexpr size_t kMaxMessageBytes = size_t{64} << 20;

ReadStatus read_message(std::istream& in, std::string& body, std::string& error);
void write_message(std::ostream& out, const std::string& body);

}  // namespace fscript::lsp
