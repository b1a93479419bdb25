// fscript-lsp: the FScript language server over standard input and output (LSP 3.17).
// Runs on a thread with a large stack, like fscript: deeply nested input never overflows it.
#include <iostream>

#include "runtime/support/big_stack.h"
#include "lsp/server.h"
#include "lsp/transport.h"

int main() {
  std::ios::sync_with_stdio(false);
  int rc = 1;
  fscript::support::run_with_big_stack([&] {
    fscript::lsp::Server server;
    std::string body, error;
    for (;;) {
      fscript::lsp::ReadStatus status = fscript::lsp::read_message(std::cin, body, error);
      if (status == fscript::lsp::ReadStatus::End) break;
      if (status == fscript::lsp::ReadStatus::BadHeader) {
        std::cerr << "fscript-lsp: skipped a message: " << error << "\n";
        continue;
      }
      for (const auto& reply : server.handle_text(body)) fscript::lsp::write_message(std::cout, reply.dump());
      if (server.exited()) break;
    }
    rc = server.exit_code();
  });
  return rc;
}
