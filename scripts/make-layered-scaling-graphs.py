#!/usr/bin/env python3
"""Graphs for the layered node's 4-to-64 scaling check (issue 36, docs/performance.md).

Writes, into OUT_DIR (default build/layered_scaling), four graphs at 1280x720, `final`:

  scatter_4.json, scatter_64.json  N small spheres spread over the view, nothing behind them
  floor_4.json,   floor_64.json    the same spheres standing on a floor that fills the view

Each is scene_join of `object` nodes (sphere of diameter 0.35 on a square grid over the same
area, ids 2 … N+1; the floor is id 1) -> gbuffer -> layered (the node's defaults apart from
the paper). Compare, in one bench session, N = 64 against N = 4 of the same layout:

  build/app/aquarelle bench OUT_DIR/scatter_4.json --size 1280x720 --quality final \
      --no-sweep --frames 5 --warmup 1          (then scatter_64, floor_4, floor_64)

Deterministic: no randomness, same files every run.
"""
import json
import math
import os
import sys


def sphere(k, x, z, diameter):
    return {
        "type": "object",
        "params": {
            "source": "sphere",
            "position": [x, diameter / 2.0, z],
            "scale": [diameter, diameter, diameter],
            "id": k,
            "color_override": True,
            "color": [0.3 + 0.6 * ((k * 37) % 11) / 10.0, 0.35 + 0.5 * ((k * 17) % 7) / 6.0,
                      0.3 + 0.6 * ((k * 29) % 5) / 4.0],
        },
    }


def graph(count, floor):
    side = int(math.isqrt(count))
    assert side * side == count
    nodes = {}
    objects = []
    if floor:
        nodes["floor"] = {
            "type": "object",
            "params": {"source": "plane", "scale": [40.0, 1.0, 40.0], "id": 1,
                       "color_override": True, "color": [0.85, 0.75, 0.55]},
        }
        objects.append("floor.object")
    # The same area for every count: 7.2 x 4.0 world units around the origin.
    for j in range(side):
        for i in range(side):
            k = 2 + j * side + i
            x = -3.6 + 7.2 * (i + 0.5) / side
            z = -2.0 + 4.0 * (j + 0.5) / side
            name = "s%d" % k
            nodes[name] = sphere(k, x, z, 0.35)
            objects.append(name + ".object")
    nodes["scene"] = {
        "type": "scene_join",
        "params": {"camera_position": [0.0, 7.0, 3.2], "camera_target": [0.0, 0.0, 0.0],
                   "fov": 60.0, "environment": "none"},
        "inputs": {"objects": objects},
    }
    nodes["gbuf"] = {"type": "gbuffer", "inputs": {"scene": "scene.scene"}}
    nodes["paper"] = {"type": "paper", "params": {"grain_scale": 160}}
    nodes["layered"] = {
        "type": "layered",
        "params": {"abstraction_sigma": 3.0, "edge_width": 2.5},
        "inputs": {"id": "gbuf.id", "normal": "gbuf.normal", "albedo": "gbuf.albedo",
                   "depth": "gbuf.depth", "paper": "paper.image", "scene": "scene.scene"},
    }
    return {
        "aquarelle": 1,
        "settings": {"width": 1280, "height": 720, "fps": 24, "frames": [1, 1],
                     "precision": "half", "quality": "final"},
        "nodes": nodes,
        "output": "layered.image",
    }


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("build", "layered_scaling")
    os.makedirs(out, exist_ok=True)
    for layout in ("scatter", "floor"):
        for count in (4, 64):
            path = os.path.join(out, "%s_%d.json" % (layout, count))
            with open(path, "w") as f:
                json.dump(graph(count, layout == "floor"), f, indent=2)
                f.write("\n")
            print(path)


if __name__ == "__main__":
    main()
