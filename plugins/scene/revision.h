// One counter for every geometry and texture revision this plugin publishes (the scene, object
// and join nodes alike), so revisions stay unique across all of its meshes, as plugin.h asks:
// two objects joined into one scene must never share one by accident.
#pragma once

#include <atomic>
#include <cstdint>

namespace scene {

inline uint64_t new_revision() {
  static std::atomic<uint64_t> next{1};
  return next.fetch_add(1);
}

}  // namespace scene
