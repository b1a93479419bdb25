// fscript-lsp: the FScript language server over standard input and output (LSP 3.17).
// Runs on a thread with a large stack, like fscript: deeply nested input never overflows it.
#include <cstring>
#include <iostream>

#include "lsp/server.h"
#include "lsp/transport.h"
#include "runtime/support/big_stack.h"
#include "runtime/support/version.h"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  fscript::support::set_default_thread_stack();  // workers' stacks not sized by ulimit -s
  for (int i = 1; i < argc; ++i) {  // clients may pass --stdio, the only transport there is
    if (std::strcmp(argv[i], "--version") == 0) {
      std::cout << fscript::support::version_line("fscript-lsp") << "\n";
      return 0;
    }
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::cout << "fscript-lsp: the FScript language server (LSP 3.17) over standard input and output\n"
                   "usage: fscript-lsp [--stdio] | --version | --help\n";
      return 0;
    }
    if (std::strcmp(argv[i], "--stdio") != 0) {
      std::cerr << "fscript-lsp: unknown argument '" << argv[i] << "' (usage: fscript-lsp [--stdio] | --version)\n";
      return 2;
    }
  }
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
