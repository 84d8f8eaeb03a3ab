// The pixels a scene's meshes may cover, as the g-buffer declares them
// (aq_host::set_output_bounds): the union of each mesh's triangle chunks' projected boxes, snapped
// out to a grid of tile_for() pixels. The light redraws exactly these pixels every frame the
// caustics move (all of them in the flagship), and everything downstream follows it, so the tighter
// they are, the less of the frame every full-size pass draws. One box per mesh (what the node
// declared before) spans the open water between a cluster's seaweed blades, over a coral's branches
// and above the sand's far edge: in the flagship at 1280x720 the meshes' boxes covered about 85 %
// of the frame, the chunks' tiles 66 % (drawn as at most 64 rects), against 56 % of pixels a mesh
// really covers.
//
// The still meshes' tiles are kept while the key of what they are drawn from stays (the node's
// cached layer key); the moving ones are added each call.
#pragma once

#include <aquarelle/plugin.h>
#include <aquarelle/sdk/region.hpp>
#include <aquarelle/sdk/static_layer.hpp>
#include <aquarelle/sdk/view_bounds.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace gbuffer {

class MeshCoverage {
 public:
  // Grid step in pixels: fine enough to follow a blade, coarse enough that a mesh's boxes mark
  // few cells and the rows give few rects; 8 at 720p, finer in a smaller target (a step of 8
  // in a thumbnail would cover more than the meshes' own boxes do).
  static int tile_for(int width, int height) {
    return std::clamp(std::min(width, height) / 90, 1, 8);
  }
  // At most this many boxes per mesh and call (a dense mesh's chunks take more triangles
  // each), so a call costs a bounded number of projections whatever the meshes' sizes. Still
  // meshes are projected once per layer, triangle by triangle; moving ones every call, four
  // triangles a box as the node's restore rects (two segments of a blade).
  static constexpr uint32_t kMaxStillChunks = 1u << 16;
  static constexpr uint32_t kMaxMovingChunks = 256;

  // The pixels of a width x height target that the meshes of `scene` may cover when drawn with
  // `view_projection`. `world_boxes`: the meshes' boxes (view_bounds::MeshBoxes), used where a
  // mesh has no triangles to chunk. `still`: meshes whose tiles may be kept under `still_key`
  // (nullptr: none, every mesh is projected this call).
  aq::Region covered(const aq_scene& scene, const std::vector<aq::view_bounds::Box>& world_boxes,
                     const std::vector<bool>* still, uint64_t still_key,
                     const glm::dmat4& view_projection, int width, int height) {
    tile_ = tile_for(width, height);
    const int columns = (width + tile_ - 1) / tile_, rows = (height + tile_ - 1) / tile_;
    if (still != nullptr) {
      if (!still_valid_ || still_key_ != still_key || width_ != width || height_ != height) {
        still_tiles_.assign(static_cast<size_t>(columns) * rows, 0);
        mark_meshes(scene, world_boxes, still, true, view_projection, width, height, &still_tiles_);
        still_key_ = still_key;
        width_ = width;
        height_ = height;
        still_valid_ = true;
      }
      tiles_ = still_tiles_;
    } else {
      still_valid_ = false;
      tiles_.assign(static_cast<size_t>(columns) * rows, 0);
    }
    mark_meshes(scene, world_boxes, still, false, view_projection, width, height, &tiles_);
    return region_of_tiles(columns, rows, width, height);
  }

 private:
  // Marks the tiles of the meshes whose `still` flag equals `which` (all meshes without flags).
  void mark_meshes(const aq_scene& scene, const std::vector<aq::view_bounds::Box>& world_boxes,
                   const std::vector<bool>* still, bool which, const glm::dmat4& view_projection,
                   int width, int height, std::vector<uint8_t>* tiles) {
    const int columns = (width + tile_ - 1) / tile_;
    for (uint32_t i = 0; i < scene.mesh_count && i < world_boxes.size(); ++i) {
      if (still != nullptr && (i >= still->size() || (*still)[i] != which)) continue;
      const aq_mesh& mesh = scene.meshes[i];
      const uint32_t triangles = mesh.index_count / 3;
      const uint32_t most = which ? kMaxStillChunks : kMaxMovingChunks;
      const uint32_t per_chunk = std::max<uint32_t>(which ? 1 : 4, (triangles + most - 1) / most);
      std::vector<aq::view_bounds::Box> chunks =
          aq::view_bounds::triangle_chunk_boxes(mesh, per_chunk);
      if (chunks.empty()) chunks.push_back(world_boxes[i]);
      for (const aq::view_bounds::Box& box : chunks) {
        const aq::PixelRect r = aq::covered_pixels(box, view_projection, width, height);
        if (r.empty()) continue;  // (a box it cannot bound gives the whole target)
        for (int ty = r.y0 / tile_; ty <= (r.y1 - 1) / tile_; ++ty)
          for (int tx = r.x0 / tile_; tx <= (r.x1 - 1) / tile_; ++tx)
            (*tiles)[static_cast<size_t>(ty) * columns + tx] = 1;
      }
    }
  }

  // Each row of tiles as runs of marked tiles; Region joins equal rows.
  aq::Region region_of_tiles(int columns, int rows, int width, int height) const {
    std::vector<aq::PixelRect> rects;
    for (int ty = 0; ty < rows; ++ty) {
      int tx = 0;
      while (tx < columns) {
        if (tiles_[static_cast<size_t>(ty) * columns + tx] == 0) {
          ++tx;
          continue;
        }
        const int start = tx;
        while (tx < columns && tiles_[static_cast<size_t>(ty) * columns + tx] != 0) ++tx;
        rects.push_back(aq::PixelRect{start * tile_, ty * tile_, std::min(tx * tile_, width),
                                      std::min((ty + 1) * tile_, height)});
      }
    }
    aq::Region region;
    region.add(rects);
    return region;
  }

  int tile_ = 8;
  std::vector<uint8_t> still_tiles_, tiles_;
  uint64_t still_key_ = 0;
  int width_ = 0, height_ = 0;
  bool still_valid_ = false;
};

}  // namespace gbuffer
