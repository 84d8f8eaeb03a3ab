// Graphs of morphology chains shared by the tests of their storage (hdr8_test: 8-bit HDR and
// 2 x 2 blocks) and of their fusion across nodes (axis_fusion_test).
#pragma once

namespace aq::test {

// erode 3, dilate 5, erode 3: the flagship's opening and closing, on an `image_input` "image".
inline constexpr const char* kMorphologyChain = R"({
  "aquarelle": 1,
  "nodes": {
    "input": {"type": "image_input", "params": {"name": "image"}},
    "open_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "input.image"}},
    "dilate": {"type": "dilate", "params": {"size": 5}, "inputs": {"image": "open_erode.image"}},
    "close_erode": {"type": "erode", "params": {"size": 3}, "inputs": {"image": "dilate.image"}}
  },
  "output": "close_erode.image"
})";

}  // namespace aq::test
