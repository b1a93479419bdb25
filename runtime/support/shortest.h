#pragma once
// The shortest decimal text that reads back as the same double or float, exactly as std::to_chars
// writes it (fixed or scientific, whichever is shorter; fixed on a tie). The browser build's
// libc++ has no floating-point to_chars: there the same text is made from printf's digits.
#include <cstddef>

namespace fscript::support {

// Writes into [buf, buf + size) and returns the end, or nullptr when it does not fit (32 bytes
// always do for a float; a double's fixed form may take up to 310).
char* shortest_text(char* buf, size_t size, double v);
char* shortest_text(char* buf, size_t size, float v);

// The printf way, on every build (tests compare it with std::to_chars where both exist).
char* shortest_text_by_printf(char* buf, size_t size, double v);
char* shortest_text_by_printf(char* buf, size_t size, float v);

}  // namespace fscript::support
