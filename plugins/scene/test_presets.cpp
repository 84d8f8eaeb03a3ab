// Small scenes for tests and debugging: a plane with a box (shadows), and the three smoothing
// cases of the task: the clay pot, a cube, and a double-sided plane.
#include "presets.h"
#include "shapes.h"

namespace scene {

bool make_test_preset(std::string_view name, Preset* preset) {
  *preset = Preset{};
  auto add = [&](MeshData mesh) {
    mesh.object_id = static_cast<uint32_t>(preset->static_meshes.size() + 1);
    preset->static_meshes.push_back(std::move(mesh));
  };
  const glm::vec3 grey(0.7f);
  if (name == "plane_box") {
    MeshData plane, box;
    add_plane(plane, 5.0f, 8, grey, false);
    add(std::move(plane));
    add_box(box, {-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, glm::vec3(0.8f, 0.3f, 0.2f));
    add(std::move(box));
  } else if (name == "pot") {
    MeshData pot;
    add_clay_pot(pot, 14, glm::vec3(0.66f, 0.32f, 0.18f));
    add(std::move(pot));
  } else if (name == "cube") {
    MeshData cube;
    add_box(cube, glm::vec3(-0.5f), glm::vec3(0.5f), glm::vec3(0.3f, 0.5f, 0.8f));
    add(std::move(cube));
  } else if (name == "double_plane") {
    MeshData plane;
    add_plane(plane, 1.0f, 4, glm::vec3(0.3f, 0.7f, 0.3f), true);
    add(std::move(plane));
  } else if (name == "three_cubes") {
    // Seed 003's scene: a red, a blue and a green cube side by side (ids 1, 2, 3).
    const glm::vec3 colors[] = {{0.8f, 0.1f, 0.08f}, {0.1f, 0.2f, 0.75f}, {0.15f, 0.6f, 0.15f}};
    for (int i = 0; i < 3; ++i) {
      MeshData cube;
      const float x = 1.7f * static_cast<float>(i - 1);
      add_box(cube, {x - 0.6f, 0.0f, -0.6f}, {x + 0.6f, 1.2f, 0.6f}, colors[i]);
      add(std::move(cube));
    }
  } else {
    return false;
  }
  return true;
}

}  // namespace scene
