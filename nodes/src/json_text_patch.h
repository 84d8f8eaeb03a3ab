// Rewriting a JSON text to hold a new value while changing only what differs, so a saved graph
// keeps the bytes of everything that was not edited: key order, line breaks, indentation and
// the exact text of numbers ("1.0" stays "1.0", [1840, 60] stays integers).
//
//   original text ──► spans of every value ──┐
//   original value (parsed) ─────────────────┼─► per value: equal → original bytes
//   updated value ───────────────────────────┘   object → members patched by key (kept in
//                                                 their order, removed ones cut with their
//                                                 separator, new ones appended in the
//                                                 siblings' style); array → by index;
//                                                 anything else → written anew
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace aq {

// `render_new` writes a value that has no original text (a new node, a changed scalar) at the
// given indentation of the line it starts on.
using JsonRenderer = std::string (*)(const nlohmann::ordered_json& value, int indent,
                                     bool expand_flat_arrays);

// The original text patched to hold `updated`; nullopt when `original` is not one JSON value.
std::optional<std::string> patch_json_text(const std::string& original,
                                           const nlohmann::ordered_json& updated,
                                           JsonRenderer render_new);

}  // namespace aq
