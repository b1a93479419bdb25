// FScript lexer. Hand-written, one pass; never fails, reports bad input as diagnostics.
#include "frontend/fscript/lexer.h"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <string>

namespace fscript::frontend {

const char* token_spelling(Tok t) {
  switch (t) {
#define FS_TOKEN(N, S) \
  case Tok::N: return S;
#define FS_KEYWORD(N, S, D) \
  case Tok::N: return S;
#include "frontend/fscript/tokens.def"
  }
  return "?";
}

bool is_keyword(Tok t) {
  switch (t) {
#define FS_KEYWORD(N, S, D) \
  case Tok::N: return true;
#include "frontend/fscript/tokens.def"
    default: return false;
  }
}

namespace {

struct Keyword {
  std::string_view word;  // lengths known at compile time: the lexer compares without strlen
  Tok tok;
};
constexpr Keyword kKeywords[] = {
#define FS_KEYWORD(N, S, D) {S, Tok::N},
#include "frontend/fscript/tokens.def"
};

// Longest punctuation first, so "===" wins over "==" and "=".
struct Punct {
  std::string_view text;
  Tok tok;
};
constexpr Punct kPuncts[] = {
    {"===", Tok::EqEqEq},     {"!==", Tok::NotEqEq},   {"==", Tok::EqEq},        {"!=", Tok::NotEq},
    {"<=", Tok::LessEq},      {">=", Tok::GreaterEq},  {"&&", Tok::AndAnd},      {"||", Tok::OrOr},
    {"++", Tok::PlusPlus},    {"--", Tok::MinusMinus}, {"**", Tok::StarStar},    {"+=", Tok::PlusAssign},
    {"-=", Tok::MinusAssign}, {"*=", Tok::StarAssign}, {"/=", Tok::SlashAssign}, {"%=", Tok::PercentAssign},
    {"^=", Tok::CaretAssign}, {"(", Tok::LParen},      {")", Tok::RParen},       {"{", Tok::LBrace},
    {"}", Tok::RBrace},       {"[", Tok::LBracket},    {"]", Tok::RBracket},     {",", Tok::Comma},
    {";", Tok::Semi},         {".", Tok::Dot},         {"?", Tok::Question},     {":", Tok::Colon},
    {"=", Tok::Assign},       {"|", Tok::Pipe},        {"&", Tok::Amp},          {"<", Tok::Less},
    {">", Tok::Greater},      {"+", Tok::Plus},        {"-", Tok::Minus},        {"*", Tok::Star},
    {"/", Tok::Slash},        {"%", Tok::Percent},     {"!", Tok::Bang},         {"^", Tok::Caret},
};

bool is_ident_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_ident_char(char c) { return is_ident_start(c) || is_digit(c); }

class Lexer {
 public:
  Lexer(const SourceFile& file, DiagnosticSink& diag) : f_(file), s_(file.text()), diag_(diag) {}

  LexResult run() {
    LexResult out;
    bool newline = false;
    bool line_empty = true;
    while (true) {
      skip_space(newline, line_empty, out.comments);
      Token t;
      t.newline_before = newline;
      newline = false;
      line_empty = false;
      if (i_ >= s_.size()) {
        t.kind = Tok::Eof;
        t.span = {u(i_), u(i_)};
        out.tokens.push_back(t);
        return out;
      }
      lex_token(t);
      out.tokens.push_back(t);
    }
  }

 private:
  static uint32_t u(size_t v) { return static_cast<uint32_t>(v); }

  void skip_space(bool& newline, bool& line_empty, std::vector<Comment>& comments) {
    while (i_ < s_.size()) {
      char c = s_[i_];
      if (c == '\n') {
        newline = true;
        line_empty = true;
        ++i_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        size_t start = i_;
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
        comments.push_back({{u(start), u(i_)}, line_empty});
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        size_t start = i_;
        size_t end = s_.find("*/", i_ + 2);
        if (end == std::string::npos) {
          diag_.error(f_, {u(start), u(start + 2)}, "unterminated comment");
          i_ = s_.size();
          return;
        }
        if (s_.find('\n', start) < end) newline = true;
        i_ = end + 2;
        comments.push_back({{u(start), u(i_)}, line_empty});
      } else {
        return;
      }
    }
  }

  void lex_token(Token& t) {
    size_t start = i_;
    char c = s_[i_];
    if (is_digit(c) || (c == '.' && i_ + 1 < s_.size() && is_digit(s_[i_ + 1]))) {
      lex_number(t);
    } else if (is_ident_start(c)) {
      while (i_ < s_.size() && is_ident_char(s_[i_])) ++i_;
      t.kind = Tok::Ident;
      std::string_view word(s_.data() + start, i_ - start);
      if (word.size() <= 8 && word[0] >= 'a' && word[0] <= 'z')  // every keyword is short and lower case
        for (const auto& k : kKeywords)
          if (k.word[0] == word[0] && word == k.word) t.kind = k.tok;
    } else if (c == '"' || c == '\'') {
      lex_string(t, c);
    } else {
      std::string_view rest(s_.data() + i_, s_.size() - i_);
      for (const auto& p : kPuncts) {
        size_t n = p.text.size();
        if (p.text[0] == c && rest.substr(0, n) == p.text) {
          t.kind = p.tok;
          i_ += n;
          t.span = {u(start), u(i_)};
          return;
        }
      }
      lex_bad_char(t);
      return;
    }
    t.span = {u(start), u(i_)};
  }

  void lex_number(Token& t) {
    size_t start = i_;
    t.kind = Tok::Number;
    if (s_[i_] == '0' && i_ + 1 < s_.size() && (s_[i_ + 1] == 'x' || s_[i_ + 1] == 'X')) {
      i_ += 2;
      size_t digits = i_;
      while (i_ < s_.size() && std::isxdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
      if (i_ == digits) diag_.error(f_, {u(start), u(i_)}, "hexadecimal number has no digits");
      t.number = static_cast<double>(std::strtoull(std::string(s_, digits, i_ - digits).c_str(), nullptr, 16));
    } else {
      while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
      if (i_ < s_.size() && s_[i_] == '.') {
        ++i_;
        while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
      }
      if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
        size_t save = i_++;
        if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
        if (i_ < s_.size() && is_digit(s_[i_])) {
          while (i_ < s_.size() && is_digit(s_[i_])) ++i_;
        } else {
          i_ = save;  // "2e" is the number 2 followed by an identifier
        }
      }
      // strtof rounds the decimal text once, straight to float (strtod then a cast could round twice).
      t.number = std::strtof(std::string(s_, start, i_ - start).c_str(), nullptr);
    }
    if (i_ < s_.size() && is_ident_start(s_[i_])) {
      size_t bad = i_;
      while (i_ < s_.size() && is_ident_char(s_[i_])) ++i_;
      // "10u", "2x": a product written as in mathematics; FScript needs the '*'.
      std::string number(s_, start, bad - start), name(s_, bad, i_ - bad);
      diag_.error(f_, {u(bad), u(i_)}, "invalid suffix on number (did you mean " + number + "*" + name + "?)");
    }
  }

  void lex_string(Token& t, char quote) {
    size_t start = i_++;
    while (i_ < s_.size() && s_[i_] != quote && s_[i_] != '\n') i_ += s_[i_] == '\\' ? 2 : 1;
    if (i_ >= s_.size() || s_[i_] != quote) {
      diag_.error(f_, {u(start), u(start + 1)}, "unterminated string");
    } else {
      ++i_;
    }
    t.kind = Tok::String;
  }

  void lex_bad_char(Token& t) {
    size_t start = i_;
    unsigned char c = static_cast<unsigned char>(s_[i_]);
    // One diagnostic for a run of bad bytes (e.g. a UTF-8 sequence), not one per byte.
    size_t len = 1;
    if (c >= 0xC0) {
      while (start + len < s_.size() && (static_cast<unsigned char>(s_[start + len]) & 0xC0) == 0x80) ++len;
    }
    i_ += len;
    std::string what;
    if (c == '#') what = "'#' is not a comment in FScript; use // or /* */";
    else if (c >= 0x20 && c < 0x7f) what = std::string("unexpected character '") + static_cast<char>(c) + "'";
    else what = "unexpected byte in source text";
    diag_.error(f_, {u(start), u(i_)}, what);
    t.kind = Tok::Error;
    t.span = {u(start), u(i_)};
  }

  const SourceFile& f_;
  const std::string& s_;
  DiagnosticSink& diag_;
  size_t i_ = 0;
};

}  // namespace

LexResult lex(const SourceFile& file, DiagnosticSink& diag) { return Lexer(file, diag).run(); }

}  // namespace fscript::frontend
