// Procedural building blocks for scenes: surfaces of revolution, boxes, planes, low-poly rocks,
// branching corals, shells, starfish, seaweed blades and the fish. Each function appends to a
// MeshData in object space (y up, resting on y = 0 unless said otherwise); placing an object
// in the world is bake_transform's job.
#pragma once

#include "mesh_data.h"
#include "random.h"

#include <glm/glm.hpp>

#include <vector>

namespace scene {

// Applies `transform` to positions and (inverse-transpose) to normals, in place.
void bake_transform(MeshData& mesh, const glm::mat4& transform);

// Surface of revolution about the y axis: `profile` is (radius, height) from start to end;
// the winding makes normals point to the left of the profile's direction of travel, i.e.
// outwards for a profile walking up the outside of a pot and inwards walking down its inside.
void add_lathe(MeshData& mesh, const std::vector<glm::vec2>& profile, int segments,
               const glm::vec3& color);

void add_box(MeshData& mesh, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& color);

// Square in the y = 0 plane, `half_size` each way, facing +y; `double_sided` adds the same
// triangles wound the other way on the very same positions (the smoothing hard case).
void add_plane(MeshData& mesh, float half_size, int cells, const glm::vec3& color,
               bool double_sided);

// The seed's test case for smoothing: a clay pot (outside, rim, inside), about 1.3 high.
void add_clay_pot(MeshData& mesh, int segments, const glm::vec3& color);

// An icosphere of radius ~1 with its vertices pushed in and out at random: a low-poly rock.
void add_rock(MeshData& mesh, Random& random, const glm::vec3& color);

// Branching coral: tapered low-poly cylinders, each branch splitting into 2-3 smaller ones.
void add_coral(MeshData& mesh, Random& random, const glm::vec3& color);

// A scallop shell: a ribbed fan, domed in the middle.
void add_shell(MeshData& mesh, const glm::vec3& color);

// A five-armed starfish lying on y = 0, radius ~1, raised along the arms' ridges.
void add_starfish(MeshData& mesh, const glm::vec3& color);

// One blade of seaweed, a tapered strip rising `height` from `root`, bent along `bend` (a
// horizontal unit direction) by offset(s) = amplitude * s^2 * sin(phase - 1.5 s), s = 0 at the
// root and 1 at the tip: a wave travelling up the blade as `phase` grows with time.
void add_seaweed_blade(MeshData& mesh, const glm::vec3& root, float height, float width,
                       float facing, const glm::vec2& bend, float amplitude, float phase,
                       const glm::vec3& color);

// A low-poly fish along +x (nose at x = +0.5, tail fin to x = -0.75), its body bent by a
// travelling wave: z += amplitude * w(x) * sin(k x - omega t), w growing towards the tail.
void add_fish(MeshData& mesh, double time, float wave_amplitude, const glm::vec3& body_color,
              const glm::vec3& fin_color);

}  // namespace scene
