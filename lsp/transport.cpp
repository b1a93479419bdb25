// Content-Length framing: headers are "Name: value" lines ending in CRLF (a bare LF is accepted),
// then a blank line, then exactly Content-Length bytes.
#include "lsp/transport.h"

#include <cctype>
#include <istream>
#include <ostream>

namespace fscript::lsp {

namespace {

bool read_line(std::istream& in, std::string& line) {
  line.clear();
  char c;
  while (in.get(c)) {
    if (c == '\n') {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return true;
    }
    line += c;
    if (line.size() > 8192) return true;  // no header is this long: let the caller reject it
  }
  return !line.empty();
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

ReadStatus read_message(std::istream& in, std::string& body, std::string& error) {
  std::string line;
  long long length = -1;
  bool any = false;
  bool bad = false;
  while (read_line(in, line)) {
    if (line.empty()) {
      if (!any) continue;  // stray blank lines between messages
      break;
    }
    any = true;
    size_t colon = line.find(':');
    if (colon == std::string::npos) {
      bad = true;
      error = "header line without ':'";
      continue;
    }
    if (lower(line.substr(0, colon)) != "content-length") continue;  // Content-Type and others
    std::string value = line.substr(colon + 1);
    size_t b = value.find_first_not_of(' ');
    value = b == std::string::npos ? "" : value.substr(b);
    if (value.empty() || value.size() > 12 || value.find_first_not_of("0123456789") != std::string::npos) {
      bad = true;
      error = "Content-Length is not a number";
      continue;
    }
    length = std::stoll(value);
  }
  if (!any) return ReadStatus::End;
  if (length < 0 || bad) {
    if (error.empty()) error = "no Content-Length header";
    return ReadStatus::BadHeader;
  }
  if (static_cast<size_t>(length) > kMaxMessageBytes) {
    error = "message of " + std::to_string(length) + " bytes is over the limit";
    in.ignore(length);
    return in ? ReadStatus::BadHeader : ReadStatus::End;
  }
  body.resize(static_cast<size_t>(length));
  in.read(body.data(), length);
  if (in.gcount() != length) return ReadStatus::End;
  return ReadStatus::Message;
}

void write_message(std::ostream& out, const std::string& body) {
  out << "Content-Length: " << body.size() << "\r\n\r\n" << body;
  out.flush();
}

}  // namespace fscript::lsp
