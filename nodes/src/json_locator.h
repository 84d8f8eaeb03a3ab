// Where things are in a JSON text. nlohmann-json 3.11 keeps no source positions and silently
// keeps the last of duplicate keys, so graph reading scans the text once more with this small
// scanner: it maps every JSON pointer to the line and column where its member (its key) or
// element starts, records duplicate keys, and finds nesting too deep to parse safely before
// any recursive code sees the text.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace aq::json_text {

struct TextPosition {
  int line = 0;    // 1-based; 0 when unknown
  int column = 0;  // 1-based, in characters (UTF-8 code points)
};

// Line and column of a byte offset (an offset at or past the end is the end of the text).
TextPosition position_of_offset(std::string_view text, size_t offset);

// The byte offset where array/object nesting first goes deeper than `limit`, or npos. Looks
// only at brackets outside strings, so it works on malformed text and never recurses.
size_t find_nesting_deeper_than(std::string_view text, int limit);

// "~" -> "~0", "/" -> "~1" (RFC 6901), so any key can be one pointer segment.
std::string escape_pointer_segment(const std::string& key);
// The segments of a pointer, unescaped: "/nodes/a~1b" -> {"nodes", "a/b"}.
std::vector<std::string> split_pointer(const std::string& pointer);

struct DuplicateKey {
  std::string pointer;  // of the member whose key repeats
  TextPosition first;   // the earlier occurrence (nlohmann drops its value)
  TextPosition second;  // the later one (the value that is kept)
};

class JsonLocator {
 public:
  // Scans `text`, which should be valid JSON nested no deeper than `max_depth`; on a syntax
  // error or a deeper nesting it stops and keeps what it found so far.
  static JsonLocator scan(std::string_view text, int max_depth);

  // Position of the value at `pointer`, or of its nearest ancestor that exists in the text
  // (so a missing member points at the object that should hold it).
  TextPosition position(const std::string& pointer) const;
  bool contains(const std::string& pointer) const { return positions_.count(pointer) != 0; }

  const std::vector<DuplicateKey>& duplicates() const { return duplicates_; }
  // The first number too large for a double (nlohmann refuses it without a position).
  bool has_overflowing_number() const { return overflow_found_; }
  TextPosition overflowing_number_position() const { return overflow_position_; }
  std::string overflowing_number() const { return overflow_text_; }

 private:
  friend class Scanner;
  std::unordered_map<std::string, TextPosition> positions_;
  std::vector<DuplicateKey> duplicates_;
  bool overflow_found_ = false;
  TextPosition overflow_position_;
  std::string overflow_text_;
};

}  // namespace aq::json_text
