// A position-tracking JSON scanner (see json_locator.h). It is a small recursive-descent
// reader that builds no values: it only follows the structure, decodes keys (so pointers match
// nlohmann's keys byte for byte) and notes where each member and element starts.
#include "json_locator.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace aq::json_text {
namespace {

bool is_continuation_byte(char c) {
  return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

void append_utf8(std::string* out, uint32_t code_point) {
  if (code_point < 0x80) {
    *out += static_cast<char>(code_point);
  } else if (code_point < 0x800) {
    *out += static_cast<char>(0xC0 | (code_point >> 6));
    *out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else if (code_point < 0x10000) {
    *out += static_cast<char>(0xE0 | (code_point >> 12));
    *out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (code_point & 0x3F));
  } else {
    *out += static_cast<char>(0xF0 | (code_point >> 18));
    *out += static_cast<char>(0x80 | ((code_point >> 12) & 0x3F));
    *out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (code_point & 0x3F));
  }
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

TextPosition position_of_offset(std::string_view text, size_t offset) {
  if (offset > text.size()) offset = text.size();
  TextPosition position{1, 1};
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++position.line;
      position.column = 1;
    } else if (!is_continuation_byte(text[i])) {
      ++position.column;
    }
  }
  return position;
}

size_t find_nesting_deeper_than(std::string_view text, int limit) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character cannot end the string
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::string_view::npos;
}

std::string escape_pointer_segment(const std::string& key) {
  std::string out;
  out.reserve(key.size());
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

std::vector<std::string> split_pointer(const std::string& pointer) {
  std::vector<std::string> segments;
  if (pointer.empty()) return segments;
  size_t start = 1;  // skip the leading '/'
  while (true) {
    const size_t slash = pointer.find('/', start);
    const std::string raw =
        pointer.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    std::string segment;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '~' && i + 1 < raw.size() && (raw[i + 1] == '0' || raw[i + 1] == '1')) {
        segment += raw[i + 1] == '0' ? '~' : '/';
        ++i;
      } else {
        segment += raw[i];
      }
    }
    segments.push_back(std::move(segment));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return segments;
}

// Walks the text once, tracking line and column as it goes. Every scan_* returns false on
// malformed input, which stops the walk (the caller already has nlohmann's own message).
class Scanner {
 public:
  Scanner(std::string_view text, int max_depth, JsonLocator* out)
      : text_(text), max_depth_(max_depth), out_(out) {}

  void run() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // a UTF-8 byte order mark
    skip_space();
    out_->positions_[""] = here();
    scan_value("", 0);
  }

 private:
  TextPosition here() const { return TextPosition{line_, column_}; }
  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }

  void advance() {
    if (at_end()) return;
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else if (!is_continuation_byte(text_[pos_])) {
      ++column_;
    }
    ++pos_;
  }

  void skip_space() {
    while (!at_end()) {
      const char c = peek();
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return;
      advance();
    }
  }

  bool expect(char c) {
    skip_space();
    if (peek() != c) return false;
    advance();
    return true;
  }

  bool scan_value(const std::string& pointer, int depth) {
    skip_space();
    switch (peek()) {
      case '{':
        return scan_object(pointer, depth + 1);
      case '[':
        return scan_array(pointer, depth + 1);
      case '"': {
        std::string ignored;
        return scan_string(&ignored);
      }
      default:
        return scan_scalar();
    }
  }

  bool scan_object(const std::string& pointer, int depth) {
    if (depth > max_depth_) return false;
    advance();  // '{'
    std::unordered_map<std::string, TextPosition> keys_here;
    skip_space();
    if (peek() == '}') {
      advance();
      return true;
    }
    while (true) {
      skip_space();
      const TextPosition key_position = here();
      std::string key;
      if (peek() != '"' || !scan_string(&key)) return false;
      const std::string member = pointer + "/" + escape_pointer_segment(key);
      auto [previous, inserted] = keys_here.emplace(key, key_position);
      if (!inserted) {
        out_->duplicates_.push_back(DuplicateKey{member, previous->second, key_position});
        previous->second = key_position;
      }
      // The last occurrence wins, as in nlohmann's value.
      out_->positions_[member] = key_position;
      if (!expect(':')) return false;
      if (!scan_value(member, depth)) return false;
      skip_space();
      if (peek() == ',') {
        advance();
        continue;
      }
      return expect('}');
    }
  }

  bool scan_array(const std::string& pointer, int depth) {
    if (depth > max_depth_) return false;
    advance();  // '['
    skip_space();
    if (peek() == ']') {
      advance();
      return true;
    }
    for (size_t index = 0;; ++index) {
      skip_space();
      const std::string element = pointer + "/" + std::to_string(index);
      out_->positions_[element] = here();
      if (!scan_value(element, depth)) return false;
      skip_space();
      if (peek() == ',') {
        advance();
        continue;
      }
      return expect(']');
    }
  }

  bool scan_hex4(uint32_t* value) {
    *value = 0;
    for (int i = 0; i < 4; ++i) {
      const int digit = hex_value(peek());
      if (digit < 0) return false;
      *value = *value * 16 + static_cast<uint32_t>(digit);
      advance();
    }
    return true;
  }

  // Decodes a string literal into UTF-8, as nlohmann does, so keys match its object keys.
  bool scan_string(std::string* out) {
    advance();  // opening quote
    while (!at_end()) {
      const char c = peek();
      if (c == '"') {
        advance();
        return true;
      }
      if (c != '\\') {
        *out += c;
        advance();
        continue;
      }
      advance();
      const char escaped = peek();
      advance();
      switch (escaped) {
        case '"':
        case '\\':
        case '/':
          *out += escaped;
          break;
        case 'b':
          *out += '\b';
          break;
        case 'f':
          *out += '\f';
          break;
        case 'n':
          *out += '\n';
          break;
        case 'r':
          *out += '\r';
          break;
        case 't':
          *out += '\t';
          break;
        case 'u': {
          uint32_t code = 0;
          if (!scan_hex4(&code)) return false;
          if (code >= 0xD800 && code <= 0xDBFF && peek() == '\\') {
            advance();
            if (peek() != 'u') return false;
            advance();
            uint32_t low = 0;
            if (!scan_hex4(&low)) return false;
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          append_utf8(out, code);
          break;
        }
        default:
          return false;
      }
    }
    return false;
  }

  // Numbers, true, false, null: consumed as one token; numbers too large for a double noted.
  bool scan_scalar() {
    const size_t start = pos_;
    const TextPosition start_position = here();
    while (!at_end()) {
      const char c = peek();
      const bool token_char = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || c == '-' ||
                              c == '+' || c == '.' || c == 'E';
      if (!token_char) break;
      advance();
    }
    if (pos_ == start) return false;
    const std::string token(text_.substr(start, pos_ - start));
    const char first = token[0];
    if (first == '-' || (first >= '0' && first <= '9')) {
      errno = 0;
      const double value = std::strtod(token.c_str(), nullptr);
      if (std::isinf(value) && !out_->overflow_found_) {
        out_->overflow_found_ = true;
        out_->overflow_position_ = start_position;
        out_->overflow_text_ = token;
      }
    }
    return true;
  }

  std::string_view text_;
  int max_depth_;
  JsonLocator* out_;
  size_t pos_ = 0;
  int line_ = 1;
  int column_ = 1;
};

JsonLocator JsonLocator::scan(std::string_view text, int max_depth) {
  JsonLocator locator;
  // About one member or element per 16 bytes in graph files; avoids rehashing big graphs.
  locator.positions_.reserve(text.size() / 16 + 16);
  Scanner(text, max_depth, &locator).run();
  return locator;
}

TextPosition JsonLocator::position(const std::string& pointer) const {
  std::string current = pointer;
  while (true) {
    auto it = positions_.find(current);
    if (it != positions_.end()) return it->second;
    if (current.empty()) return TextPosition{};
    const size_t slash = current.rfind('/');
    current.erase(slash == std::string::npos ? 0 : slash);
  }
}

}  // namespace aq::json_text
