// What a scene preset is: static meshes (generated once per seed, uploaded once) and animated
// objects (rebuilt when time changes). The scene node turns a Preset into an aq_scene.
#pragma once

#include "mesh_data.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace aq {
class Context;
}

namespace scene {

struct AnimationSettings {
  double fish_speed = 0.35;  // radians per second around the loop
  double sway = 1.0;         // seaweed sway amplitude factor (0 freezes it)
};

// The largest `sway` the node accepts; animated bounds are sized for it so the scene's bounds
// (and with them the shadow map's fit) do not move from frame to frame.
constexpr double kMaxSway = 3.0;

struct AnimatedObject {
  uint32_t object_id = 0;
  glm::vec3 bounds_min{0.0f};  // world space, holds the object at every time
  glm::vec3 bounds_max{0.0f};
  // Fills `mesh` (cleared by the caller) for `time` seconds: vertices and model matrix.
  std::function<void(double time, const AnimationSettings&, MeshData& mesh)> build;
};

struct Preset {
  std::vector<MeshData> static_meshes;
  std::vector<AnimatedObject> animated;
};

// The seed's Figure 1: sand tray, rocks, corals, seaweed, shells, starfish, two clay pots, and a
// fish swimming a loop. Same seed, same scene, on every machine.
// `detail` scales the sand tray's cell count (1 for a full-size render, the render scale for a
// proxy one).
Preset make_underwater(uint64_t seed, double detail = 1.0);

// Small scenes for tests: "plane_box" (10x10 ground plane, id 1, and a unit box on it, id 2),
// "pot" (the clay pot, id 1), "cube" (unit cube centred at the origin, id 1), "double_plane"
// (a 2x2 plane at y = 0 with both windings on the same positions, id 1).
bool make_test_preset(std::string_view name, Preset* preset);

// Loads every mesh of an OBJ, glTF or other Assimp-readable file placed as at time 0, with
// material base colours and textures. Returns an empty string or a message saying what failed.
// Textures are read through the host (`ctx`, cached in `textures`); what is missing is a warning.
class TextureCache;
std::string load_model_file(const std::string& path, Preset* preset, const aq::Context& ctx,
                            TextureCache& textures);

}  // namespace scene
