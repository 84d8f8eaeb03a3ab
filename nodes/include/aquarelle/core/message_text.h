// User text inside messages (paths, node ids, parameter names, values) is escaped: a newline
// in a file name would forge a whole `file:line:col: ...` line, an ESC sequence could clear
// the terminal or retitle it. Control characters (C0, DEL and the C1 range as UTF-8) become
// visible escapes (\n, \t, \x1b, \u009b); everything else, UTF-8 included, stays as it is.
// Escaping twice changes nothing more than escaping once would show.
#pragma once

#include <cstdio>
#include <string>

namespace aq {

inline std::string escape_for_message(const std::string& text, bool keep_newlines = false) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n' && keep_newlines) {
      out += '\n';
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c < 0x20 || c == 0x7f) {
      char code[8];
      std::snprintf(code, sizeof(code), "\\x%02x", c);
      out += code;
    } else if (c == 0xc2 && i + 1 < text.size() &&
               static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
               static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
      char code[8];
      std::snprintf(code, sizeof(code), "\\u%04x", static_cast<unsigned char>(text[++i]));
      out += code;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

// 'text', escaped: for paths and names inside a message.
inline std::string quote_for_message(const std::string& text) {
  return "'" + escape_for_message(text) + "'";
}

}  // namespace aq
