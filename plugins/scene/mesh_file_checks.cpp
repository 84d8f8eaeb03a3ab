#include "mesh_file_checks.h"

#include <aquarelle/sdk/regular_file.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <optional>
#include <vector>

namespace scene {

namespace {

// zlib's deflate reaches at most 1032:1; a little slack covers headers and rounding.
constexpr uint64_t kDeflateMaxRatio = 1100;

// Assimp keeps well under this per declared vertex or face of a PLY element.
constexpr uint64_t kBytesPerElementInMemory = 64;

// What Assimp's glTF reader holds per accessor element beyond the accessor's own copy: the
// vertex it becomes and, for points, a face of its own (measured: 40 M sparse points took
// 3.1 GB, about 78 bytes each).
constexpr uint64_t kAssimpBytesPerElement = 80;

std::string mib(uint64_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

// a * b, saturating at UINT64_MAX.
uint64_t times(uint64_t a, uint64_t b) {
  if (a != 0 && b > UINT64_MAX / a) return UINT64_MAX;
  return a * b;
}
uint64_t plus(uint64_t a, uint64_t b) {
  return b > UINT64_MAX - a ? UINT64_MAX : a + b;
}

// ---- PLY ------------------------------------------------------------------------------

int ply_type_size(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t at = 0;
  while (at < line.size()) {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r')) ++at;
    size_t end = at;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '\r') ++end;
    if (end > at) out.push_back(line.substr(at, end - at));
    at = end;
  }
  return out;
}

std::optional<uint64_t> parse_count(std::string_view text) {
  if (text.empty() || text.size() > 19) return std::nullopt;
  uint64_t value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + static_cast<uint64_t>(c - '0');
  }
  return value;
}

// ---- glTF -----------------------------------------------------------------------------

// Deepest nesting of JSON arrays and objects, strings skipped; no recursion.
int json_nesting(std::string_view text) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return deepest;
}

std::optional<uint64_t> unsigned_at(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return std::nullopt;
  auto it = object.find(key);
  if (it == object.end() || !it->is_number_unsigned()) {
    if (it != object.end() && it->is_number_integer() && it->get<int64_t>() >= 0) {
      return static_cast<uint64_t>(it->get<int64_t>());
    }
    return std::nullopt;
  }
  return it->get<uint64_t>();
}

const nlohmann::json* array_at(const nlohmann::json& root, const char* key) {
  auto it = root.find(key);
  if (it == root.end() || !it->is_array()) return nullptr;
  return &*it;
}

int components_of(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

int component_bytes(uint64_t type) {
  switch (type) {
    case 5120:
    case 5121:
      return 1;
    case 5122:
    case 5123:
      return 2;
    case 5125:
    case 5126:
      return 4;
    default:
      return 0;
  }
}

// Node hierarchy: every index in range, no node with two parents or on a cycle, depth
// bounded. Iterative, so a hostile depth cannot overflow this check's own stack.
std::string check_hierarchy(const nlohmann::json& root) {
  const nlohmann::json* nodes = array_at(root, "nodes");
  if (nodes == nullptr) return "";
  const size_t count = nodes->size();
  std::vector<int64_t> parent(count, -1);
  for (size_t i = 0; i < count; ++i) {
    const nlohmann::json& node = (*nodes)[i];
    if (!node.is_object()) continue;
    auto children = node.find("children");
    if (children == node.end() || !children->is_array()) continue;
    for (const auto& child : *children) {
      if (!child.is_number_integer() || child.get<int64_t>() < 0 ||
          static_cast<uint64_t>(child.get<int64_t>()) >= count) {
        return "node " + std::to_string(i) + " has a child index out of range";
      }
      const auto c = static_cast<size_t>(child.get<int64_t>());
      if (parent[c] != -1 || c == i) {
        return "node " + std::to_string(c) + " has two parents or is its own child";
      }
      parent[c] = static_cast<int64_t>(i);
    }
  }
  // Depth of each node by walking up; cycles show up as walks longer than the node count.
  std::vector<int> depth(count, 0);
  for (size_t i = 0; i < count; ++i) {
    if (depth[i] != 0) continue;
    std::vector<size_t> chain;
    int64_t at = static_cast<int64_t>(i);
    while (at != -1 && depth[static_cast<size_t>(at)] == 0) {
      chain.push_back(static_cast<size_t>(at));
      if (chain.size() > count) return "the node hierarchy has a cycle";
      at = parent[static_cast<size_t>(at)];
    }
    int d = at == -1 ? 0 : depth[static_cast<size_t>(at)];
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      depth[*it] = ++d;
      if (d > kMaxMeshHierarchyDepth) {
        return "its node hierarchy is more than " + std::to_string(kMaxMeshHierarchyDepth) +
               " levels deep (flatten it in your modelling tool)";
      }
    }
  }
  return "";
}

}  // namespace

bool is_inside_folder(const std::string& folder_canonical, const std::string& canonical) {
  if (folder_canonical.empty()) return false;
  std::string folder = folder_canonical;
  if (folder.back() != '/') folder += '/';
  return canonical.size() > folder.size() && canonical.compare(0, folder.size(), folder) == 0;
}

std::string reference_problem(const std::string& folder, const std::string& reference) {
  if (reference.find('\0') != std::string::npos) {
    return "it refers to a file name with a NUL character";
  }
  std::error_code ec;
  const std::filesystem::path base = std::filesystem::weakly_canonical(folder, ec);
  if (ec) return "its folder " + folder + " cannot be resolved";
  std::filesystem::path target = reference;
  if (target.is_relative()) target = base / target;
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(target, ec);
  if (ec || !is_inside_folder(base.string(), resolved.string())) {
    return "it refers to '" + reference + "', which lies outside the mesh's folder " +
           base.string() + " (files a mesh refers to must be inside its folder)";
  }
  if (std::string why = aq::files::regular_file_problem(resolved.string()); !why.empty()) {
    return "it refers to '" + reference + "': " + why;
  }
  return "";
}

std::string check_ply_header(std::string_view bytes, uint64_t file_size, uint64_t budget) {
  const size_t end = bytes.find("end_header");
  if (bytes.substr(0, 3) != "ply") return "it does not start with 'ply'";
  if (end == std::string_view::npos) return "its header has no end_header line";
  size_t body = bytes.find('\n', end);
  body = body == std::string_view::npos ? bytes.size() : body + 1;
  uint64_t data_bytes = file_size > body ? file_size - body : 0;

  bool ascii = true;
  struct Element {
    std::string name;
    uint64_t count = 0;
    uint64_t least_bytes = 0;  // per element: fixed properties, plus list counts
  };
  std::vector<Element> elements;
  std::string_view header = bytes.substr(0, end);
  size_t at = 0;
  while (at < header.size()) {
    size_t eol = header.find('\n', at);
    if (eol == std::string_view::npos) eol = header.size();
    const auto w = words(header.substr(at, eol - at));
    at = eol + 1;
    if (w.empty()) continue;
    if (w[0] == "format" && w.size() >= 2) {
      ascii = w[1] == "ascii";
    } else if (w[0] == "element" && w.size() >= 3) {
      auto count = parse_count(w[2]);
      if (!count) return "its element '" + std::string(w[1]) + "' has no valid count";
      elements.push_back({std::string(w[1]), *count, 0});
    } else if (w[0] == "property" && !elements.empty()) {
      uint64_t least = 0;
      if (w.size() >= 5 && w[1] == "list") {
        least = ascii ? 2 : static_cast<uint64_t>(std::max(ply_type_size(w[2]), 1));
      } else if (w.size() >= 3) {
        least = ascii ? 2 : static_cast<uint64_t>(std::max(ply_type_size(w[1]), 1));
      }
      elements.back().least_bytes += least;
    }
  }
  if (ascii) ++data_bytes;  // the last value may go without its line break
  uint64_t least_total = 0, memory = 0;
  for (const Element& e : elements) {
    // An ASCII element takes at least a line even without properties.
    const uint64_t per = std::max<uint64_t>(e.least_bytes, ascii ? 1 : 0);
    least_total = plus(least_total, times(e.count, per));
    memory = plus(memory, times(e.count, kBytesPerElementInMemory));
    if (times(e.count, per) > data_bytes) {
      return "its header declares " + std::to_string(e.count) + " " + e.name +
             " elements, which need at least " + std::to_string(times(e.count, per)) +
             " bytes, but only " + std::to_string(data_bytes) +
             " bytes follow the header (the file is truncated or its header is forged)";
    }
  }
  if (least_total > data_bytes) {
    return "its header declares elements needing at least " + std::to_string(least_total) +
           " bytes, but only " + std::to_string(data_bytes) + " bytes follow the header";
  }
  if (memory > budget) {
    return "reading its declared elements would need about " + mib(memory) +
           ", more than the memory budget of " + mib(budget) +
           " (simplify the mesh, or raise AQUARELLE_MEMORY_BUDGET_MB)";
  }
  return "";
}

std::string check_gltf_json(std::string_view json, const std::string& folder,
                            int64_t bin_chunk_bytes, uint64_t budget) {
  if (json_nesting(json) > kMaxGltfJsonNesting) {
    return "its JSON is nested more than " + std::to_string(kMaxGltfJsonNesting) + " levels deep";
  }
  const nlohmann::json root = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (root.is_discarded() || !root.is_object()) return "its JSON cannot be parsed";
  if (std::string problem = check_hierarchy(root); !problem.empty()) return problem;

  std::vector<uint64_t> buffer_bytes;
  if (const nlohmann::json* buffers = array_at(root, "buffers")) {
    for (size_t i = 0; i < buffers->size(); ++i) {
      const nlohmann::json& buffer = (*buffers)[i];
      const std::string name = "buffer " + std::to_string(i);
      auto length = unsigned_at(buffer, "byteLength");
      if (!length) return name + " has no valid byteLength";
      if (*length > budget) {
        return name + " declares " + mib(*length) + ", more than the memory budget of " +
               mib(budget) + " (raise AQUARELLE_MEMORY_BUDGET_MB if the file is genuine)";
      }
      auto uri = buffer.is_object() ? buffer.find("uri") : buffer.end();
      if (!buffer.is_object() || uri == buffer.end()) {
        if (bin_chunk_bytes < 0 || static_cast<uint64_t>(bin_chunk_bytes) < *length) {
          return name + " declares " + std::to_string(*length) +
                 " bytes but the file's binary chunk holds " +
                 std::to_string(std::max<int64_t>(bin_chunk_bytes, 0));
        }
      } else if (!uri->is_string()) {
        return name + " has a uri that is not a string";
      } else {
        const std::string text = uri->get<std::string>();
        if (text.rfind("data:", 0) == 0) {
          const size_t comma = text.find(',');
          const uint64_t payload = comma == std::string::npos ? 0 : text.size() - comma - 1;
          if (payload / 4 * 3 + 3 < *length) {
            return name + " declares " + std::to_string(*length) +
                   " bytes but its data URI holds fewer";
          }
        } else if (!folder.empty()) {
          if (std::string why = reference_problem(folder, text); !why.empty()) {
            return name + ": " + why;
          }
          std::filesystem::path file = text;
          if (file.is_relative()) file = std::filesystem::path(folder) / file;
          const uint64_t size = aq::files::regular_file_size(file.string());
          if (size < *length) {
            return name + " declares " + std::to_string(*length) + " bytes but '" + text +
                   "' holds " + std::to_string(size);
          }
        }
      }
      buffer_bytes.push_back(*length);
    }
  }
  std::vector<uint64_t> view_bytes;
  if (const nlohmann::json* views = array_at(root, "bufferViews")) {
    for (size_t i = 0; i < views->size(); ++i) {
      const nlohmann::json& view = (*views)[i];
      const std::string name = "bufferView " + std::to_string(i);
      auto buffer = unsigned_at(view, "buffer");
      auto length = unsigned_at(view, "byteLength");
      const uint64_t offset = unsigned_at(view, "byteOffset").value_or(0);
      if (!buffer || *buffer >= buffer_bytes.size()) return name + " names no buffer";
      if (!length || plus(offset, *length) > buffer_bytes[*buffer]) {
        return name + " reaches past the end of buffer " + std::to_string(*buffer);
      }
      view_bytes.push_back(*length);
    }
  }
  uint64_t accessor_bytes = 0;
  if (const nlohmann::json* accessors = array_at(root, "accessors")) {
    for (size_t i = 0; i < accessors->size(); ++i) {
      const nlohmann::json& accessor = (*accessors)[i];
      const std::string name = "accessor " + std::to_string(i);
      auto count = unsigned_at(accessor, "count");
      auto component = unsigned_at(accessor, "componentType");
      auto type = accessor.is_object() ? accessor.find("type") : accessor.end();
      if (!count || !component || !accessor.is_object() || type == accessor.end() ||
          !type->is_string()) {
        return name + " lacks count, componentType or type";
      }
      const uint64_t element = static_cast<uint64_t>(component_bytes(*component)) *
                               static_cast<uint64_t>(components_of(type->get<std::string>()));
      if (element == 0) return name + " has an unknown componentType or type";
      // Every accessor is read whole (a sparse one too: 595 bytes declaring 100 M points),
      // then copied into Assimp's vertices and faces: the budget holds them all together.
      accessor_bytes = plus(accessor_bytes, times(*count, plus(element, kAssimpBytesPerElement)));
      if (accessor_bytes > budget) {
        return name + " declares " + std::to_string(*count) + " elements; reading the accessors " +
               "up to it needs about " + mib(accessor_bytes) + ", more than the memory budget of " +
               mib(budget) + " (simplify the mesh, or raise AQUARELLE_MEMORY_BUDGET_MB)";
      }
      auto view = unsigned_at(accessor, "bufferView");
      if (!view) continue;  // all zeros (or sparse): no data to check against
      if (*view >= view_bytes.size()) return name + " names no bufferView";
      const uint64_t offset = unsigned_at(accessor, "byteOffset").value_or(0);
      if (*count > 0 && plus(offset, times(*count, element)) > plus(view_bytes[*view], element)) {
        // Interleaved strides make the exact end smaller; count x element bounds it below.
        if (plus(offset, times(*count - 1, element)) > view_bytes[*view]) {
          return name + " declares " + std::to_string(*count) + " elements, more than bufferView " +
                 std::to_string(*view) + " holds";
        }
      }
    }
  }
  if (const nlohmann::json* images = array_at(root, "images"); images && !folder.empty()) {
    for (size_t i = 0; i < images->size(); ++i) {
      const nlohmann::json& image = (*images)[i];
      if (!image.is_object()) continue;
      auto uri = image.find("uri");
      if (uri == image.end() || !uri->is_string()) continue;
      const std::string text = uri->get<std::string>();
      if (text.rfind("data:", 0) == 0) continue;
      if (std::string why = reference_problem(folder, text); !why.empty()) {
        return "image " + std::to_string(i) + ": " + why;
      }
    }
  }
  return "";
}

std::string check_glb(std::string_view bytes, const std::string& folder, uint64_t budget) {
  auto u32 = [&](size_t at) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;  // GLB is little-endian, as is every machine this builds on
  };
  if (bytes.size() < 12 || bytes.substr(0, 4) != "glTF") return "it has no GLB header";
  const uint32_t version = u32(4);
  const uint32_t length = u32(8);
  if (length > bytes.size()) {
    return "its header declares " + std::to_string(length) + " bytes but the file has " +
           std::to_string(bytes.size()) + " (truncated or forged)";
  }
  if (version != 2) return "";  // glTF 1 binary: Assimp's own checks
  std::string_view json;
  int64_t bin = -1;
  size_t at = 12;
  while (at + 8 <= length) {
    const uint32_t chunk = u32(at);
    const uint32_t type = u32(at + 4);
    if (chunk > length - at - 8) {
      return "a chunk at byte " + std::to_string(at) + " declares " + std::to_string(chunk) +
             " bytes but only " + std::to_string(length - at - 8) + " remain (truncated or forged)";
    }
    if (type == 0x4E4F534Au && json.empty()) json = bytes.substr(at + 8, chunk);  // "JSON"
    if (type == 0x004E4942u && bin < 0) bin = chunk;                              // "BIN\0"
    at += 8 + static_cast<size_t>(chunk);
  }
  if (json.empty()) return "it has no JSON chunk";
  return check_gltf_json(json, folder, bin, budget);
}

namespace {

// Bytes per element of an FBX array property, 0 for a type that is not an array.
uint64_t fbx_array_element_bytes(char type) {
  switch (type) {
    case 'b':
      return 1;
    case 'i':
    case 'f':
      return 4;
    case 'l':
    case 'd':
      return 8;
    default:
      return 0;
  }
}

// Binary FBX: node records (end offset, property count, property bytes, name) holding typed
// properties and nested records up to a null record. Assimp allocates an array property's
// element count times its size before inflating it, and follows end offsets as given.
std::string check_fbx_binary(std::string_view bytes, uint64_t budget) {
  constexpr size_t kHeader = 27;  // "Kaydara FBX Binary  \0", 0x1a 0x00, u32 version
  if (bytes.size() < kHeader) return "its header is cut short";
  uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 23, 4);
  const bool wide = version >= 7500;  // 64-bit record fields from FBX 7.5 on
  const size_t field = wide ? 8 : 4;
  const uint64_t size = bytes.size();
  auto read_uint = [&](uint64_t at, size_t width) {
    uint64_t value = 0;
    std::memcpy(&value, bytes.data() + at, width);  // little-endian, as every machine here
    return value;
  };
  // Ends of the records whose children are being read; at the top level, the file's end.
  std::vector<uint64_t> ends;
  uint64_t at = kHeader;
  while (true) {
    const uint64_t limit = ends.empty() ? size : ends.back();
    if (at + 3 * field + 1 > limit) {  // no room for another record: this list ends
      if (ends.empty()) break;
      at = ends.back();
      ends.pop_back();
      continue;
    }
    const uint64_t end = read_uint(at, field);
    const uint64_t properties = read_uint(at + field, field);
    const uint64_t property_bytes = read_uint(at + 2 * field, field);
    const uint64_t name_length = static_cast<uint8_t>(bytes[at + 3 * field]);
    if (end == 0 && properties == 0 && property_bytes == 0 && name_length == 0) {
      if (ends.empty()) break;  // the null record ending the top level
      at = ends.back();         // the null record ending a record's children
      ends.pop_back();
      continue;
    }
    const uint64_t body = at + 3 * field + 1 + name_length;
    if (end > limit || end < body || property_bytes > end - body) {
      return "a record at byte " + std::to_string(at) + " declares its end at byte " +
             std::to_string(end) + " with " + std::to_string(property_bytes) +
             " bytes of properties, outside the " + std::to_string(limit) +
             " bytes it may use (truncated or forged)";
    }
    if (properties > property_bytes) {
      return "a record at byte " + std::to_string(at) + " declares " + std::to_string(properties) +
             " properties in " + std::to_string(property_bytes) + " bytes (truncated or forged)";
    }
    uint64_t p = body;
    const uint64_t properties_end = body + property_bytes;
    for (uint64_t i = 0; i < properties; ++i) {
      if (p >= properties_end) return "a record's properties run past their declared size";
      const char type = bytes[p++];
      const uint64_t element = fbx_array_element_bytes(type);
      uint64_t payload = 0;
      if (element != 0) {
        if (p + 12 > properties_end) return "an array property is cut short";
        const uint64_t count = read_uint(p, 4);
        const uint64_t encoding = read_uint(p + 4, 4);
        const uint64_t stored = read_uint(p + 8, 4);
        p += 12;
        const uint64_t decoded = times(count, element);
        if (encoding == 0 ? decoded != stored
                          : decoded > plus(times(stored, kDeflateMaxRatio), 65536)) {
          return "an array property at byte " + std::to_string(p - 13) + " declares " +
                 std::to_string(count) + " elements in " + std::to_string(stored) +
                 " stored bytes (truncated or forged)";
        }
        if (decoded > budget) {
          return "an array property declares " + mib(decoded) +
                 ", more than the memory budget of " + mib(budget) +
                 " (raise AQUARELLE_MEMORY_BUDGET_MB or simplify the model)";
        }
        payload = stored;
      } else if (type == 'S' || type == 'R') {
        if (p + 4 > properties_end) return "a string property is cut short";
        payload = read_uint(p, 4);
        p += 4;
      } else if (type == 'Y') {
        payload = 2;
      } else if (type == 'C') {
        payload = 1;
      } else if (type == 'I' || type == 'F') {
        payload = 4;
      } else if (type == 'D' || type == 'L') {
        payload = 8;
      } else {
        return "a property at byte " + std::to_string(p - 1) + " has an unknown type";
      }
      if (payload > properties_end - p) {
        return "a property at byte " + std::to_string(p) + " declares " + std::to_string(payload) +
               " bytes past its record (truncated or forged)";
      }
      p += payload;
    }
    if (properties_end < end) {  // children follow the properties
      if (ends.size() >= static_cast<size_t>(kMaxMeshHierarchyDepth)) {
        return "its records nest deeper than " + std::to_string(kMaxMeshHierarchyDepth);
      }
      ends.push_back(end);
      at = properties_end;
    } else {
      at = end;
    }
  }
  return "";
}

// ASCII FBX: Assimp reserves an array's declared count ("*N {") before reading its values;
// each value takes at least two characters (a digit and a comma).
std::string check_fbx_ascii(std::string_view bytes, uint64_t file_size) {
  for (size_t at = bytes.find('*'); at != std::string_view::npos; at = bytes.find('*', at + 1)) {
    size_t digits = at + 1;
    while (digits < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[digits]))) {
      ++digits;
    }
    if (digits == at + 1) continue;
    const auto count = parse_count(bytes.substr(at + 1, digits - at - 1));
    if (!count || times(*count, 2) > file_size + 2) {
      return "an array declares " +
             std::string(bytes.substr(at + 1, std::min<size_t>(digits - at - 1, 20))) +
             " values but the file has " + std::to_string(file_size) +
             " bytes (truncated or forged)";
    }
  }
  return "";
}

std::string check_fbx(std::string_view bytes, uint64_t file_size, uint64_t budget) {
  static constexpr std::string_view kBinaryMagic("Kaydara FBX Binary  \0", 21);
  if (bytes.substr(0, kBinaryMagic.size()) == kBinaryMagic) {
    return check_fbx_binary(bytes, budget);
  }
  return check_fbx_ascii(bytes, file_size);
}

}  // namespace

std::string check_mesh_file_bytes(const std::string& ext, std::string_view bytes,
                                  uint64_t file_size, const std::string& folder, uint64_t budget) {
  if (ext == "ply") return check_ply_header(bytes, file_size, budget);
  if (ext == "gltf") return check_gltf_json(bytes, folder, -1, budget);
  if (ext == "glb") return check_glb(bytes, folder, budget);
  if (ext == "fbx") return check_fbx(bytes, file_size, budget);
  if (ext == "obj") return check_obj(bytes, budget);
  return "";
}

}  // namespace scene

namespace scene {

std::string check_mesh_file_size(uint64_t file_size, uint64_t budget) {
  if (times(file_size, kFileBytesInMemory) <= budget) return "";
  return "it is " + mib(file_size) + "; reading a mesh file of that size needs more than the " +
         "memory budget of " + mib(budget) +
         " (split the mesh, or raise AQUARELLE_MEMORY_BUDGET_MB)";
}

uint64_t count_obj_meshes(std::string_view bytes) {
  uint64_t meshes = 0;
  size_t at = 0;
  while (at < bytes.size()) {
    size_t eol = bytes.find('\n', at);
    if (eol == std::string_view::npos) eol = bytes.size();
    const std::string_view line = bytes.substr(at, eol - at);
    at = eol + 1;
    if (line.size() >= 2 && (line[0] == 'o' || line[0] == 'g') &&
        (line[1] == ' ' || line[1] == '\t')) {
      ++meshes;
    } else if (line.rfind("usemtl", 0) == 0) {
      ++meshes;
    }
  }
  return meshes;
}

std::string obj_meshes_problem(uint64_t meshes, uint64_t budget) {
  // Assimp's cost per mesh of an OBJ (its aiMesh, material and node), measured about 10 KB.
  constexpr uint64_t kBytesPerMesh = 16 << 10;
  if (meshes > kMaxObjMeshes || times(meshes, kBytesPerMesh) > budget) {
    return "it declares " + std::to_string(meshes) + " objects, groups or material changes; at " +
           "most " + std::to_string(kMaxObjMeshes) + " are read (merge them in the modelling tool)";
  }
  return "";
}

std::string check_obj(std::string_view bytes, uint64_t budget) {
  return obj_meshes_problem(count_obj_meshes(bytes), budget);
}

namespace {

// One PLY property: a fixed-size value, or a list (count type, item type).
struct PlyProperty {
  bool list = false;
  int count_size = 0;
  int size = 0;  // the value's, or a list item's
};
struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// Reads a little- or big-endian unsigned count of `size` bytes.
uint64_t decode_count(const char* bytes, int size, bool big_endian) {
  uint64_t value = 0;
  for (int i = 0; i < size; ++i) {
    const int at = big_endian ? i : size - 1 - i;
    value = (value << 8) | static_cast<unsigned char>(bytes[at]);
  }
  return value;
}

// Whitespace-separated words of an ASCII PLY body, read through `read` in small windows.
class PlyWords {
 public:
  PlyWords(uint64_t offset, uint64_t file_size,
           const std::function<bool(uint64_t, char*, size_t)>& read)
      : offset_(offset), size_(file_size), read_(read) {}
  // The next word (at most 24 characters kept), false at the end of the file.
  bool next(std::string* word) {
    word->clear();
    char c = 0;
    do {
      if (!get(&c)) return false;
    } while (is_space(c));
    do {
      if (word->size() < 24) word->push_back(c);
    } while (get(&c) && !is_space(c));
    return true;
  }
  uint64_t offset() const { return offset_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
  bool get(char* c) {
    if (at_ == window_.size()) {
      const uint64_t left = size_ > offset_ ? size_ - offset_ : 0;
      window_.resize(static_cast<size_t>(std::min<uint64_t>(left, 4096)));
      at_ = 0;
      if (window_.empty() || !read_(offset_, window_.data(), window_.size())) {
        window_.clear();
        return false;
      }
    }
    *c = window_[at_++];
    ++offset_;
    return true;
  }
  uint64_t offset_, size_;
  const std::function<bool(uint64_t, char*, size_t)>& read_;
  std::string window_;
  size_t at_ = 0;
};

// ASCII PLY: each list item takes at least two bytes (a digit and a separator; the last may go
// without one), so a count larger than half of what is left cannot be right (a 190-byte face
// declaring 268 M indices made Assimp take 4.4 GB and 12 s). Only counts are checked, not
// numbers; a body that is not what the header says is left to Assimp's own message.
std::string check_ply_ascii_lists(const std::vector<PlyElement>& elements, uint64_t body,
                                  uint64_t file_size,
                                  const std::function<bool(uint64_t, char*, size_t)>& read) {
  PlyWords words(body, file_size, read);
  std::string word;
  for (const PlyElement& e : elements) {
    for (uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (!words.next(&word)) return "";
        if (!p.list) continue;
        const auto count = parse_count(word);
        if (!count) return "";
        const uint64_t left = file_size - std::min(words.offset(), file_size);
        if (*count > left / 2 + 1) {
          return "a " + e.name + " element declares a list of " + word + " items, more than the " +
                 std::to_string(left) +
                 " bytes left in the file hold (the file is truncated or forged)";
        }
        for (uint64_t item = 0; item < *count; ++item) {
          if (!words.next(&word)) return "";
        }
      }
    }
  }
  return "";
}

}  // namespace

std::string check_ply_body(std::string_view header, uint64_t file_size,
                           const std::function<bool(uint64_t, char*, size_t)>& read) {
  const size_t end = header.find("end_header");
  if (end == std::string_view::npos) return "";
  size_t body = header.find('\n', end);
  body = body == std::string_view::npos ? header.size() : body + 1;
  std::string format = "ascii";
  std::vector<PlyElement> elements;
  size_t at = 0;
  while (at < end) {
    size_t eol = header.find('\n', at);
    if (eol == std::string_view::npos || eol > end) eol = end;
    const auto w = words(header.substr(at, eol - at));
    at = eol + 1;
    if (w.empty()) continue;
    if (w[0] == "format" && w.size() >= 2) format = std::string(w[1]);
    if (w[0] == "element" && w.size() >= 3) {
      elements.push_back({std::string(w[1]), parse_count(w[2]).value_or(0), {}});
    } else if (w[0] == "property" && !elements.empty()) {
      if (w.size() >= 5 && w[1] == "list") {
        elements.back().properties.push_back({true, ply_type_size(w[2]), ply_type_size(w[3])});
      } else if (w.size() >= 3) {
        elements.back().properties.push_back({false, 0, ply_type_size(w[1])});
      }
    }
  }
  const bool big_endian = format == "binary_big_endian";
  uint64_t offset = body;
  auto too_long = [&](const PlyElement& e, uint64_t count) {
    return "a " + e.name + " element declares a list of " + std::to_string(count) +
           " items, more than the " + std::to_string(file_size - std::min(offset, file_size)) +
           " bytes left in the file hold (the file is truncated or forged)";
  };
  if (format == "ascii") return check_ply_ascii_lists(elements, body, file_size, read);
  for (const PlyElement& e : elements) {
    for (uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (p.size == 0 || (p.list && p.count_size == 0)) return "";  // unknown type: Assimp's
        if (!p.list) {
          offset = plus(offset, static_cast<uint64_t>(p.size));
          continue;
        }
        char bytes[8] = {};
        if (!read(offset, bytes, static_cast<size_t>(p.count_size))) {
          return "its " + e.name + " elements end before the file says (truncated)";
        }
        const uint64_t count = decode_count(bytes, p.count_size, big_endian);
        offset = plus(offset, static_cast<uint64_t>(p.count_size));
        const uint64_t items = times(count, static_cast<uint64_t>(p.size));
        if (plus(offset, items) > file_size) return too_long(e, count);
        offset = plus(offset, items);
      }
      if (offset > file_size) return "its " + e.name + " elements end before the file says";
    }
  }
  return "";
}

}  // namespace scene
