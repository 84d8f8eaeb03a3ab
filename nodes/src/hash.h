// FNV-1a, for the evaluator's cache keys: cheap, stable across runs and machines.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace aq {

inline constexpr uint64_t kHashSeed = 1469598103934665603ull;

inline uint64_t hash_bytes(uint64_t h, const void* data, size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= 1099511628211ull;
  }
  return h;
}

inline uint64_t hash_string(uint64_t h, const std::string& s) {
  h = hash_bytes(h, s.data(), s.size());
  return hash_bytes(h, "\0", 1);  // so ("ab","c") and ("a","bc") differ
}

template <typename T>
uint64_t hash_value(uint64_t h, const T& v) {
  return hash_bytes(h, &v, sizeof(v));
}

}  // namespace aq
