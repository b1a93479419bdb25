// VRML97 lexer (ISO/IEC 14772-1, 5.1 and annex A).
#include "frontend/vrml/vrml_lexer.h"

#include <cctype>

namespace fscript::vrml {
namespace {

bool id_first(unsigned char c) {
  if (c <= 0x20 || c == 0x7f) return false;
  switch (c) {
    case '"':
    case '#':
    case '\'':
    case '+':
    case ',':
    case '-':
    case '.':
    case '[':
    case '\\':
    case ']':
    case '{':
    case '}': return false;
    default: return !(c >= '0' && c <= '9');
  }
}

bool id_rest(unsigned char c) {
  if (c <= 0x20 || c == 0x7f) return false;
  switch (c) {
    case '"':
    case '#':
    case '\'':
    case ',':
    case '.':
    case '[':
    case '\\':
    case ']':
    case '{':
    case '}': return false;
    default: return true;
  }
}

// Length of the UTF-8 sequence at s[i], or 0 if it is not valid UTF-8.
size_t utf8_length(const std::string& s, size_t i) {
  unsigned char c = static_cast<unsigned char>(s[i]);
  size_t n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
  return n;
}

class Lexer {
 public:
  Lexer(const frontend::SourceFile& f, size_t start, frontend::DiagnosticSink& d)
      : f_(f), s_(f.text()), i_(start), d_(d) {}

  std::vector<VToken> run() {
    std::vector<VToken> out;
    while (true) {
      skip();
      VToken t;
      t.span = {u(i_), u(i_)};
      if (i_ >= s_.size()) {
        out.push_back(t);
        return out;
      }
      token(t);
      t.span.end = u(i_);
      out.push_back(std::move(t));
    }
  }

 private:
  static uint32_t u(size_t v) { return static_cast<uint32_t>(v); }

  void skip() {
    while (i_ < s_.size()) {
      char c = s_[i_];
      if (c == '#') {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
        ++i_;
      } else {
        return;
      }
    }
  }

  void token(VToken& t) {
    unsigned char c = static_cast<unsigned char>(s_[i_]);
    switch (c) {
      case '[':
        t.kind = VTok::LBracket;
        ++i_;
        return;
      case ']':
        t.kind = VTok::RBracket;
        ++i_;
        return;
      case '{':
        t.kind = VTok::LBrace;
        ++i_;
        return;
      case '}':
        t.kind = VTok::RBrace;
        ++i_;
        return;
      case '"': return string(t);
      default: break;
    }
    if (std::isdigit(c) || c == '+' || c == '-' ||
        (c == '.' && i_ + 1 < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_ + 1]))))
      return number(t);
    if (c == '.') {
      t.kind = VTok::Period;
      ++i_;
      return;
    }
    if (id_first(c)) return ident(t);
    bad(t);
  }

  void ident(VToken& t) {
    size_t b = i_;
    while (i_ < s_.size() && id_rest(static_cast<unsigned char>(s_[i_]))) {
      size_t n = utf8_length(s_, i_);
      if (n == 0) {
        d_.error(f_, {u(i_), u(i_ + 1)}, "invalid UTF-8 in a name");
        ++i_;
        continue;
      }
      i_ += n;
    }
    t.kind = VTok::Id;
    t.text = s_.substr(b, i_ - b);
  }

  void number(VToken& t) {
    size_t b = i_;
    if (s_[i_] == '+' || s_[i_] == '-') ++i_;
    if (i_ + 1 < s_.size() && s_[i_] == '0' && (s_[i_ + 1] == 'x' || s_[i_ + 1] == 'X')) {
      i_ += 2;
      while (i_ < s_.size() && std::isxdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
    } else {
      while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
      if (i_ < s_.size() && s_[i_] == '.') ++i_;
      while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
      if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
        size_t save = i_++;
        if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
        if (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_])))
          while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
        else i_ = save;
      }
    }
    t.kind = VTok::Number;
    t.text = s_.substr(b, i_ - b);
    if (t.text == "+" || t.text == "-") {
      d_.error(f_, {u(b), u(i_)}, "'" + t.text + "' is not a number");
      t.kind = VTok::Error;
    }
  }

  void string(VToken& t) {
    size_t b = i_++;
    t.kind = VTok::String;
    while (i_ < s_.size() && s_[i_] != '"') {
      if (s_[i_] == '\\' && i_ + 1 < s_.size()) ++i_;  // \" and \\ (any escaped byte is itself)
      size_t n = utf8_length(s_, i_);
      if (n == 0) {
        d_.error(f_, {u(i_), u(i_ + 1)}, "invalid UTF-8 in a string");
        ++i_;
        continue;
      }
      t.text.append(s_, i_, n);
      i_ += n;
    }
    if (i_ >= s_.size()) {
      d_.error(f_, {u(b), u(b + 1)}, "unterminated string");
      return;
    }
    ++i_;
  }

  void bad(VToken& t) {
    size_t b = i_;
    size_t n = utf8_length(s_, i_);
    i_ += n ? n : 1;
    std::string what = n == 0 ? "invalid UTF-8" : "unexpected character '" + s_.substr(b, i_ - b) + "'";
    d_.error(f_, {u(b), u(i_)}, what);
    t.kind = VTok::Error;
  }

  const frontend::SourceFile& f_;
  const std::string& s_;
  size_t i_;
  frontend::DiagnosticSink& d_;
};

}  // namespace

std::vector<VToken> lex_vrml(const frontend::SourceFile& file, size_t start, frontend::DiagnosticSink& diag) {
  return Lexer(file, start, diag).run();
}

}  // namespace fscript::vrml
