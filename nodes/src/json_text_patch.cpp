// Patching a JSON text in place of rewriting it. See json_text_patch.h.
#include "json_text_patch.h"

#include <string_view>
#include <vector>

namespace aq {
namespace {

// Where one value sits in the text; objects and arrays also list their members (an array's
// members have no key).
struct TextValue {
  struct Member;
  size_t begin = 0;
  size_t end = 0;   // one past the last character
  char kind = 's';  // '{', '[' or 's' (a scalar)
  std::vector<Member> members;
};

struct TextValue::Member {
  std::string key;
  size_t key_begin = 0;  // the opening quote; for array elements the value's begin
  TextValue value;
};

// Spans of a text already known to be valid JSON (nlohmann::json::accept).
class SpanParser {
 public:
  explicit SpanParser(const std::string& text) : text_(text) {}

  bool parse(TextValue* out) {
    skip_space();
    if (!value(out, 0)) return false;
    skip_space();
    return at_ == text_.size();
  }

 private:
  void skip_space() {
    while (at_ < text_.size() &&
           (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n' || text_[at_] == '\r')) {
      ++at_;
    }
  }

  bool string_token(std::string* decoded) {
    const size_t begin = at_++;
    while (at_ < text_.size() && text_[at_] != '"') at_ += text_[at_] == '\\' ? 2 : 1;
    if (at_ >= text_.size()) return false;
    ++at_;
    if (decoded != nullptr) {
      *decoded = nlohmann::json::parse(text_.substr(begin, at_ - begin)).get<std::string>();
    }
    return true;
  }

  bool value(TextValue* out, int depth) {
    if (depth > 512 || at_ >= text_.size()) return false;
    out->begin = at_;
    const char first = text_[at_];
    if (first == '{' || first == '[') {
      out->kind = first;
      const char close = first == '{' ? '}' : ']';
      ++at_;
      skip_space();
      if (at_ < text_.size() && text_[at_] == close) {
        out->end = ++at_;
        return true;
      }
      while (at_ < text_.size()) {
        TextValue::Member member;
        member.key_begin = at_;
        if (first == '{') {
          if (text_[at_] != '"' || !string_token(&member.key)) return false;
          skip_space();
          if (at_ >= text_.size() || text_[at_] != ':') return false;
          ++at_;
          skip_space();
        }
        if (!value(&member.value, depth + 1)) return false;
        out->members.push_back(std::move(member));
        skip_space();
        if (at_ >= text_.size()) return false;
        if (text_[at_] == close) {
          out->end = ++at_;
          return true;
        }
        if (text_[at_] != ',') return false;
        ++at_;
        skip_space();
      }
      return false;
    }
    out->kind = 's';
    if (first == '"') {
      if (!string_token(nullptr)) return false;
    } else {
      while (at_ < text_.size() &&
             std::string_view(",}] \t\r\n").find(text_[at_]) == std::string_view::npos) {
        ++at_;
      }
    }
    out->end = at_;
    return true;
  }

  const std::string& text_;
  size_t at_ = 0;
};

class Patcher {
 public:
  Patcher(const std::string& text, JsonRenderer render, bool expand)
      : text_(text), render_(render), expand_(expand) {}

  std::string patch(const TextValue& span, const nlohmann::ordered_json& old,
                    const nlohmann::ordered_json& updated) const {
    if (old == updated) return slice(span.begin, span.end);
    const bool same_kind =
        (span.kind == '{' && updated.is_object()) || (span.kind == '[' && updated.is_array());
    if (same_kind && !span.members.empty()) return patch_members(span, old, updated);
    if (!updated.is_structured()) {
      return updated.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }
    return render_(updated, line_indent(span.begin), expand_);
  }

 private:
  std::string slice(size_t begin, size_t end) const { return text_.substr(begin, end - begin); }

  // Spaces at the start of the line holding `position`.
  int line_indent(size_t position) const {
    size_t line = text_.rfind('\n', position == 0 ? 0 : position - 1);
    line = line == std::string::npos ? 0 : line + 1;
    int indent = 0;
    while (line + indent < text_.size() && text_[line + indent] == ' ') ++indent;
    return indent;
  }

  std::string patch_members(const TextValue& span, const nlohmann::ordered_json& old,
                            const nlohmann::ordered_json& updated) const {
    const bool object = span.kind == '{';
    const auto& members = span.members;
    auto kept = [&](size_t i) {
      return object ? updated.contains(members[i].key) : i < updated.size();
    };
    auto old_of = [&](size_t i) -> const nlohmann::ordered_json& {
      static const nlohmann::ordered_json kNull;
      if (object) return old.contains(members[i].key) ? old.at(members[i].key) : kNull;
      return i < old.size() ? old.at(i) : kNull;
    };
    auto new_of = [&](size_t i) -> const nlohmann::ordered_json& {
      return object ? updated.at(members[i].key) : updated.at(i);
    };
    const std::string prefix = slice(span.begin, members.front().key_begin);
    const std::string suffix = slice(members.back().value.end, span.end);
    // A new member follows the last separator, or the layout of the opening.
    std::string separator = ", ";
    if (members.size() > 1) {
      separator = slice(members[members.size() - 2].value.end, members.back().key_begin);
    } else if (prefix.find('\n') != std::string::npos) {
      separator = "," + prefix.substr(1);
    }
    const size_t newline = separator.rfind('\n');
    const int member_indent = newline == std::string::npos
                                  ? line_indent(span.begin)
                                  : static_cast<int>(separator.size() - newline - 1);

    std::string out = prefix;
    bool first = true;
    for (size_t i = 0; i < members.size(); ++i) {
      if (!kept(i)) continue;
      if (!first) out += slice(members[i - 1].value.end, members[i].key_begin);
      first = false;
      out += slice(members[i].key_begin, members[i].value.begin);
      out += patch(members[i].value, old_of(i), new_of(i));
    }
    auto append = [&](const std::string& head, const nlohmann::ordered_json& value) {
      if (!first) out += separator;
      first = false;
      out += head;
      out += value.is_structured()
                 ? render_(value, member_indent, expand_)
                 : value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    };
    if (object) {
      const std::string colon = slice(members.front().key_begin, members.front().value.begin)
                                    .substr(nlohmann::json(members.front().key).dump().size());
      for (const auto& [key, value] : updated.items()) {
        bool known = false;
        for (const auto& member : members) known = known || member.key == key;
        if (!known) append(nlohmann::json(key).dump() + colon, value);
      }
    } else {
      for (size_t i = members.size(); i < updated.size(); ++i) append("", updated.at(i));
    }
    if (first) return object ? "{}" : "[]";
    return out + suffix;
  }

  const std::string& text_;
  JsonRenderer render_;
  bool expand_;
};

// Whether the text writes arrays of plain values one element per line (Python's json.dump
// style) rather than on one line: the first such array decides.
bool expands_flat_arrays(const TextValue& span, const std::string& text, bool* decided) {
  if (span.kind == '[' && !span.members.empty()) {
    bool flat = true;
    for (const auto& member : span.members) flat = flat && member.value.kind == 's';
    if (flat) {
      *decided = true;
      return text.substr(span.begin, span.end - span.begin).find('\n') != std::string::npos;
    }
  }
  for (const auto& member : span.members) {
    bool expand = expands_flat_arrays(member.value, text, decided);
    if (*decided) return expand;
  }
  return false;
}

}  // namespace

std::optional<std::string> patch_json_text(const std::string& original,
                                           const nlohmann::ordered_json& updated,
                                           JsonRenderer render_new) {
  if (!nlohmann::ordered_json::accept(original)) return std::nullopt;
  const auto old = nlohmann::ordered_json::parse(original);
  TextValue root;
  if (!SpanParser(original).parse(&root)) return std::nullopt;
  bool decided = false;
  const bool expand = expands_flat_arrays(root, original, &decided);
  Patcher patcher(original, render_new, expand);
  // Whatever surrounds the value (a trailing newline) stays as it was.
  return original.substr(0, root.begin) + patcher.patch(root, old, updated) +
         original.substr(root.end);
}

}  // namespace aq
