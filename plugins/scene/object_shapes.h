// The procedural shapes an `object` node can be instead of a file, and the uvs a texture on
// them is sampled with.
#pragma once

#include "mesh_data.h"

#include <string_view>

namespace scene {

// Names of the shapes, in the order of the object node's `source` enum after "file".
// "terrain" is built by make_terrain (terrain.h) from the object's terrain parameters.
inline constexpr const char* kObjectShapes[] = {"cube",     "sphere", "plane",  "card",
                                                "pot",      "rock",   "coral",  "shell",
                                                "starfish", "fish",   "terrain"};

// Builds shape `name` (object space, y up, resting on y = 0 except the cube and sphere, which
// are centred at the origin, unit size) at `time` (only the fish moves: its body wave).
// Planes and cards come with uvs; other shapes get box-projected uvs when textured.
void make_object_shape(std::string_view name, double time, uint64_t seed, MeshData& mesh);

// uvs by box projection: each vertex projects along its normal's dominant axis onto the
// mesh's bounding box faces, scaled to 0..1.
void box_project_uvs(MeshData& mesh);

}  // namespace scene
