#!/usr/bin/env python3
"""Writes the small models and textures of graphs/files.json and graphs/deep_ocean.json into
assets/scenes/ (each file well under 100 KB): OBJ/MTL/PNG and glTF (external and embedded
textures, keyframes), and the deep ocean's ship with cut-out sails, jellyfish, kelp and the
equirectangular panorama of its surroundings. All procedural: no third-party asset.
Deterministic: same script, same bytes. Run from anywhere: scripts/make-scene-assets.py"""
import base64
import json
import math
import os
import random
import struct
import zlib

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "scenes")


def png(path, width, height, pixel):
    """8-bit RGBA PNG; pixel(x, y) -> (r, g, b, a) in 0..255, y = 0 the top row."""
    rows = b""
    for y in range(height):
        rows += b"\0" + bytes(c for x in range(width) for c in pixel(x, y))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    data = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
    if path:
        with open(os.path.join(OUT, path), "wb") as f:
            f.write(data)
    return data


def clamp(v):
    return max(0, min(255, int(round(v))))


def sand(x, y):
    r = random.Random(x * 131 + y * 7919)
    grain = r.uniform(-18, 18)
    ripple = 14 * math.sin((x + 0.6 * y) * 2 * math.pi / 16)
    return (clamp(214 + grain + ripple), clamp(190 + grain + ripple), clamp(140 + grain * 0.8 + ripple), 255)


def seaweed(x, y, w=32, h=64):
    # A wavy blade: opaque green inside, transparent outside (a cut-out card).
    t = 1 - y / (h - 1)  # 0 at the bottom row (y = h - 1), 1 at the top
    centre = w / 2 + 5 * math.sin(t * 5.0) * t
    half = (w * 0.32) * (1 - 0.75 * t) + 1
    inside = abs(x + 0.5 - centre) < half
    vein = abs(x + 0.5 - centre) < 1.2
    g = 150 + 60 * t - (40 if vein else 0)
    return (clamp(40 + 30 * t), clamp(g), clamp(60), 255 if inside else 0)


def stripes(x, y):
    # Fish skin: orange with white bands, seen on a mesh whose u runs nose to tail.
    band = (x // 6) % 3 == 1
    return (250, 250, 245, 255) if band else (250, 120, 30, 255)


def checker(x, y):
    return (230, 200, 90, 255) if (x // 4 + y // 4) % 2 == 0 else (190, 80, 60, 255)


def star(x, y):
    d = math.hypot(x - 7.5, y - 7.5)
    return (clamp(250 - 6 * d), clamp(120 - 4 * d), clamp(60), 255)


def write(name, text):
    with open(os.path.join(OUT, name), "w", newline="\n") as f:
        f.write(text)


def obj_floor():
    # 4x4 quads, 8x8 world units, uvs repeat the sand 4 times.
    lines = ["# sand floor (made by scripts/make-scene-assets.py)", "mtllib floor.mtl", "usemtl sand"]
    n = 4
    for j in range(n + 1):
        for i in range(n + 1):
            x, z = -4 + 8 * i / n, -4 + 8 * j / n
            lines.append("v %g %g %g" % (x, 0.05 * math.sin(x * 1.3) * math.cos(z), z))
            lines.append("vt %g %g" % (4 * i / n, 4 * (n - j) / n))
    lines.append("vn 0 1 0")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            b, c, d = a + 1, a + n + 2, a + n + 1
            lines.append("f %d/%d/1 %d/%d/1 %d/%d/1" % (a, a, d, d, c, c))
            lines.append("f %d/%d/1 %d/%d/1 %d/%d/1" % (a, a, c, c, b, b))
    write("floor.obj", "\n".join(lines) + "\n")
    write("floor.mtl", "newmtl sand\nKd 1 1 1\nmap_Kd sand.png\n")
    png("sand.png", 32, 32, sand)


def obj_rock():
    # A jittered octahedron subdivided once: a low-poly rock, Kd only (no texture).
    r = random.Random(5)
    base = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (4, 2, 1), (1, 2, 5), (5, 2, 0), (4, 3, 0), (1, 3, 4), (5, 3, 1), (0, 3, 5)]
    verts = [list(v) for v in base]
    mids = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in mids:
            p = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
            length = math.sqrt(sum(c * c for c in p))
            verts.append([c / length for c in p])
            mids[key] = len(verts) - 1
        return mids[key]

    fine = []
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        fine += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    lines = ["# rock (made by scripts/make-scene-assets.py)", "mtllib rock.mtl", "usemtl stone"]
    for v in verts:
        s = r.uniform(0.8, 1.1)
        lines.append("v %.4f %.4f %.4f" % (v[0] * s * 0.6, v[1] * s * 0.4 + 0.3, v[2] * s * 0.5))
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in fine]
    write("rock.obj", "\n".join(lines) + "\n")
    write("rock.mtl", "newmtl stone\nKd 0.42 0.40 0.44\n")


def obj_card():
    # A seaweed card as a file: a unit-wide, two-high quad standing on y = 0, alpha cut-out.
    write("seaweed.obj", "# seaweed card (made by scripts/make-scene-assets.py)\nmtllib seaweed.mtl\n"
          "usemtl blade\nv -0.5 0 0\nv 0.5 0 0\nv 0.5 2 0\nv -0.5 2 0\n"
          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n")
    write("seaweed.mtl", "newmtl blade\nKd 1 1 1\nmap_Kd seaweed.png\n")
    png("seaweed.png", 32, 64, seaweed)


def obj_fish():
    # A fish along +x (nose at +0.5), a lathe of elliptic rings with a tail fin; u runs along
    # the body so the stripes go round it.
    rings = [(0.5, 0.0), (0.42, 0.09), (0.3, 0.15), (0.12, 0.18), (-0.08, 0.16), (-0.25, 0.11),
             (-0.38, 0.06), (-0.47, 0.03)]
    sides = 10
    lines = ["# fish (made by scripts/make-scene-assets.py)", "mtllib fish.mtl", "usemtl skin"]
    for x, r in rings:
        for j in range(sides + 1):
            t = 2 * math.pi * j / sides
            lines.append("v %.4f %.4f %.4f" % (x, r * math.cos(t), 0.55 * r * math.sin(t)))
            lines.append("vt %.4f %.4f" % ((0.5 - x), j / sides))
    for i in range(len(rings) - 1):
        for j in range(sides):
            a = i * (sides + 1) + j + 1
            b, c, d = a + 1, a + sides + 2, a + sides + 1
            lines.append("f %d/%d %d/%d %d/%d" % (a, a, b, b, c, c))
            lines.append("f %d/%d %d/%d %d/%d" % (a, a, c, c, d, d))
    base = len(rings) * (sides + 1)
    lines += ["v -0.45 0 0", "v -0.78 0.26 0", "v -0.66 0 0", "v -0.78 -0.26 0",
              "vt 0.95 0.5", "vt 1 1", "vt 1 0.5", "vt 1 0"]
    lines += ["f %d/%d %d/%d %d/%d" % (base + 1, base + 1, base + 2, base + 2, base + 3, base + 3),
              "f %d/%d %d/%d %d/%d" % (base + 1, base + 1, base + 3, base + 3, base + 4, base + 4)]
    write("fish.obj", "\n".join(lines) + "\n")
    write("fish.mtl", "newmtl skin\nKd 1 1 1\nmap_Kd fish.png\n")
    png("fish.png", 36, 8, stripes)


def gltf_box(name, texture_uri_or_bytes, factor, animated=False):
    """A unit box (centred at y = 0.5) with per-face uvs, COLOR_0 white, a base colour texture
    (a file beside it, or embedded as a data URI), and optionally keyframes: a slow bob and turn."""
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    pos, nor, uv, col, idx = [], [], [], [], []
    for n, u, v in faces:
        start = len(pos)
        for su, sv in [(0, 0), (1, 0), (1, 1), (0, 1)]:
            p = [0.5 * n[k] + (su - 0.5) * u[k] + (sv - 0.5) * v[k] for k in range(3)]
            p[1] += 0.5
            pos.append(p)
            nor.append(n)
            uv.append((su, 1 - sv))  # glTF: v = 0 is the image's top row
            col.append((1.0, 1.0, 1.0, 1.0))
        idx += [start, start + 1, start + 2, start, start + 2, start + 3]
    blob = b"".join(struct.pack("<3f", *p) for p in pos)
    blob += b"".join(struct.pack("<3f", *n) for n in nor)
    blob += b"".join(struct.pack("<2f", *t) for t in uv)
    blob += b"".join(struct.pack("<4f", *c) for c in col)
    blob += b"".join(struct.pack("<H", i) for i in idx)
    blob += b"\0" * ((4 - len(blob) % 4) % 4)
    nv = len(pos)
    views = [(0, 12 * nv), (12 * nv, 12 * nv), (24 * nv, 8 * nv), (32 * nv, 16 * nv), (48 * nv, 2 * len(idx))]
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3",
         "min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5]},
        {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": nv, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5126, "count": nv, "type": "VEC4"},
        {"bufferView": 4, "componentType": 5123, "count": len(idx), "type": "SCALAR"}]
    animations = []
    if animated:
        times = [0.0, 1.0, 2.0]
        offset = len(blob)
        blob += b"".join(struct.pack("<f", t) for t in times)
        blob += b"".join(struct.pack("<3f", 0, y, 0) for y in [0.0, 0.6, 0.0])
        half = math.sqrt(0.5)
        rots = [(0, 0, 0, 1), (0, half, 0, half), (0, 1, 0, 0)]
        blob += b"".join(struct.pack("<4f", *q) for q in rots)
        views += [(offset, 12), (offset + 12, 36), (offset + 48, 48)]
        accessors += [
            {"bufferView": 5, "componentType": 5126, "count": 3, "type": "SCALAR", "min": [0], "max": [2]},
            {"bufferView": 6, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 7, "componentType": 5126, "count": 3, "type": "VEC4"}]
        animations = [{"name": "bob", "samplers": [
            {"input": 5, "output": 6, "interpolation": "LINEAR"},
            {"input": 5, "output": 7, "interpolation": "LINEAR"}],
            "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                         {"sampler": 1, "target": {"node": 0, "path": "rotation"}}]}]
    if isinstance(texture_uri_or_bytes, bytes):
        image = {"uri": "data:image/png;base64," + base64.b64encode(texture_uri_or_bytes).decode()}
    else:
        image = {"uri": texture_uri_or_bytes}
    doc = {
        "asset": {"version": "2.0", "generator": "scripts/make-scene-assets.py"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "box", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "COLOR_0": 3},
                                    "indices": 4, "material": 0}]}],
        "materials": [{"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(factor) + [1.0], "baseColorTexture": {"index": 0},
            "metallicFactor": 0.0}}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987}],
        "images": [image],
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," +
                     base64.b64encode(blob).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": l} for o, l in views],
        "accessors": accessors}
    if animations:
        doc["animations"] = animations
    write(name + ".gltf", json.dumps(doc, indent=1) + "\n")


def sail(x, y, w=64, h=64):
    # Worn canvas: alpha 255 where whole, 0 in the tears along the bottom and a hole, and 204
    # (0.8, under the ship's cut-off 0.9) in a thin worn patch: discarded like the tears.
    r = random.Random(x * 977 + y * 31)
    stain = 18 * math.sin(x * 0.31) * math.sin(y * 0.23)
    colour = (clamp(232 + stain + r.uniform(-6, 6)), clamp(222 + stain), clamp(190 + stain * 0.6))
    ragged = h - 1 - y < 5 + 4 * math.sin(x * 0.9) + 3 * math.sin(x * 0.37)
    hole = math.hypot(x - 40, y - 22) < 5
    worn = abs(x - 18) < 3 and 10 < y < 40
    alpha = 0 if ragged or hole else 204 if worn else 255
    return colour + (alpha,) if alpha else (0, 0, 0, 0)


def kelp(x, y):
    return seaweed(x, y, 32, 128)


def panorama(x, y, w=512, h=256):
    # Under the sea, looking around: light from the surface above (a glow at the zenith and
    # shafts radiating down), fading to the deep blue below the horizon.
    lat = (0.5 - (y + 0.5) / h) * math.pi
    lon = (x + 0.5) / w * 2 * math.pi
    up = max(math.sin(lat), 0.0)
    glow = math.exp(-((math.pi / 2 - lat) ** 2) / 0.12)
    shafts = 0.5 + 0.5 * math.sin(lon * 23 + 3 * math.sin(lon * 7))
    down = max(-math.sin(lat), 0.0)
    r = 6 + 40 * up ** 1.5 + 150 * glow + 18 * shafts * up - 4 * down
    g = 38 + 110 * up ** 1.5 + 190 * glow + 40 * shafts * up - 26 * down
    b = 62 + 120 * up ** 1.2 + 170 * glow + 40 * shafts * up - 40 * down
    return (clamp(r), clamp(g), clamp(b), 255)


def planks(x, y, w=64, h=64):
    # Hull planking: horizontal strakes (dark seams every 8 rows), butt joints staggered
    # along each strake, and a little grain.
    r = random.Random(x * 131 + y * 7)
    strake = y // 8
    seam = y % 8 == 0
    butt = (x + 23 * strake) % 40 == 0
    grain = 10 * math.sin(x * 0.7 + strake * 1.9) + r.uniform(-5, 5)
    if seam or butt:
        return (70, 44, 26, 255)
    return (clamp(150 + grain), clamp(104 + grain * 0.8), clamp(64 + grain * 0.5), 255)


def hull_section(x):
    """Half-beam, keel depth and deck height of the hull at station x (bow at +0.5, transom
    at -0.5): a full midship section fining to a pointed stem, a sheer that rises fore and aft,
    and a transom narrower than the midship beam."""
    beam = 0.17 * (1 - ((x + 0.05) / 0.55) ** 2) ** 0.5 if x > -0.05 else 0.17 - 0.05 * ((-0.05 - x) / 0.45) ** 2
    keel = -0.02 - 0.11 * max(1 - ((x + 0.02) / 0.52) ** 4, 0.0) ** 0.5
    deck = 0.16 + 0.07 * ((x + 0.02) / 0.52) ** 2 + (0.04 if x < -0.3 else 0.0) * ((-0.3 - x) / 0.2)
    return max(beam, 0.0), keel, deck


def obj_ship():
    # A small sailing ship along +x (bow at +0.5), seen in the deep ocean as a wreck: a hull
    # lofted through round-bilged sections (a keel, a sheer rising fore and aft, a pointed stem,
    # a transom), planked (uvs along the hull and round the girth), a deck, a raised stern
    # castle, a bowsprit, two masts, and two square sails (planes across the hull, uvs 0..1)
    # with the cut-out canvas.
    lines = ["# ship (made by scripts/make-scene-assets.py)", "mtllib ship.mtl", "usemtl hull"]
    stations = [-0.5 + i / 20 for i in range(21)]
    # Girth from the port deck edge (-1) down round the keel (0) to the starboard deck edge
    # (+1): (side across, 0 at the keel .. 1 at the deck).
    girth = [-1.0, -0.9, -0.75, -0.55, -0.3, 0.0, 0.3, 0.55, 0.75, 0.9, 1.0]
    n = len(girth)
    for x in stations:
        beam, keel, deck = hull_section(x)
        for g in girth:
            a = abs(g)
            # Round bilge: the side is vertical near the deck, turning into a V at the keel;
            # a slight tumblehome (narrower at the deck than at the widest point).
            across = beam * math.sin(a * math.pi / 2) ** 0.6 * (1 - 0.08 * a ** 6)
            up = keel + (deck - keel) * (1 - math.cos(a * math.pi / 2))
            lines.append("v %.4f %.4f %.4f" % (x, up, math.copysign(across, g)))
    for i, x in enumerate(stations):
        for g in girth:
            lines.append("vt %.4f %.4f" % ((x + 0.5) * 4, (g + 1) * 2))
    for i in range(len(stations) - 1):
        for j in range(n - 1):
            a = i * n + j + 1
            lines.append("f %d/%d %d/%d %d/%d" % (a, a, a + n, a + n, a + n + 1, a + n + 1))
            lines.append("f %d/%d %d/%d %d/%d" % (a, a, a + n + 1, a + n + 1, a + 1, a + 1))
    # The transom closes the stern (a fan from the keel).
    transom = list(range(1, n + 1))
    for j in range(1, n - 1):
        lines.append("f %d/%d %d/%d %d/%d" % (transom[0], transom[0], transom[j + 1], transom[j + 1],
                                              transom[j], transom[j]))
    count = len(stations) * n
    uvs = count
    lines.append("usemtl wood")
    # The deck: a strip between the port and starboard deck edges, a little below them.
    for x in stations:
        beam, keel, deck = hull_section(x)
        lines.append("v %.4f %.4f %.4f" % (x, deck - 0.015, -beam * 0.92))
        lines.append("v %.4f %.4f %.4f" % (x, deck - 0.015, beam * 0.92))
    for i in range(len(stations) - 1):
        a = count + 2 * i + 1
        lines.append("f %d %d %d" % (a, a + 1, a + 3))
        lines.append("f %d %d %d" % (a, a + 3, a + 2))
    count += 2 * len(stations)

    def box(lo, hi):
        nonlocal count
        for k in range(8):
            lines.append("v %.4f %.4f %.4f" % (hi[0] if k & 1 else lo[0], hi[1] if k & 2 else lo[1],
                                               hi[2] if k & 4 else lo[2]))
        for f in ((1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)):
            lines.append("f " + " ".join(str(count + v) for v in f))
        count += 8

    def spar(a, b, r):
        # A square spar from point a to point b (thickness 2r), as eight vertices.
        nonlocal count
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dy)
        nx, ny = -dy / length * r, dx / length * r
        for k in range(8):
            end = b if k & 1 else a
            side = 1 if k & 2 else -1
            lines.append("v %.4f %.4f %.4f" % (end[0] + side * nx, end[1] + side * ny, r if k & 4 else -r))
        for f in ((1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)):
            lines.append("f " + " ".join(str(count + v) for v in f))
        count += 8

    box((-0.5, 0.2, -0.14), (-0.3, 0.3, 0.14))       # stern castle
    box((-0.49, 0.3, -0.13), (-0.31, 0.315, 0.13))   # its rail
    box((0.03, 0.15, -0.012), (0.055, 1.0, 0.012))   # main mast
    box((0.31, 0.15, -0.01), (0.33, 0.8, 0.01))      # fore mast
    box((-0.005, 0.93, -0.29), (0.015, 0.955, 0.29))  # main yard
    box((0.325, 0.74, -0.21), (0.34, 0.76, 0.21))     # fore yard
    spar((0.46, 0.2), (0.72, 0.33), 0.01)             # bowsprit
    lines.append("usemtl canvas")
    uv = uvs
    for x, y0, y1, half in ((0.07, 0.38, 0.92, 0.26), (0.345, 0.36, 0.73, 0.19)):
        for yy, zz in ((y0, -half), (y0, half), (y1, half), (y1, -half)):
            lines.append("v %.4f %.4f %.4f" % (x, yy, zz))
        lines += ["vt 0 0", "vt 1 0", "vt 1 1", "vt 0 1"]
        lines.append("f %d/%d %d/%d %d/%d" % (count + 1, uv + 1, count + 2, uv + 2, count + 3, uv + 3))
        lines.append("f %d/%d %d/%d %d/%d" % (count + 1, uv + 1, count + 3, uv + 3, count + 4, uv + 4))
        count += 4
        uv += 4
    write("ship.obj", "\n".join(lines) + "\n")
    write("ship.mtl", "newmtl hull\nKd 1 1 1\nmap_Kd hull.png\n\nnewmtl wood\nKd 0.55 0.38 0.22\n\n"
          "newmtl canvas\nKd 1 1 1\nmap_Kd sail.png\n")
    png("sail.png", 64, 64, sail)
    png("hull.png", 64, 64, planks)


def obj_jellyfish():
    # A bell (a lathe of a rounded profile) with eight wavy tentacles hanging from its rim,
    # about 1 high; pale pink, bright enough to glow through the fog.
    lines = ["# jellyfish (made by scripts/make-scene-assets.py)", "mtllib jellyfish.mtl", "usemtl bell"]
    profile = [(0.0, 1.0), (0.16, 0.97), (0.29, 0.88), (0.37, 0.74), (0.39, 0.62), (0.33, 0.6),
               (0.22, 0.64)]
    sides = 16
    for r, y in profile:
        for j in range(sides):
            t = 2 * math.pi * j / sides
            lines.append("v %.4f %.4f %.4f" % (r * math.cos(t), y, r * math.sin(t)))
    for i in range(len(profile) - 1):
        for j in range(sides):
            a = i * sides + j + 1
            b = i * sides + (j + 1) % sides + 1
            lines.append("f %d %d %d" % (a, b + sides, b))
            lines.append("f %d %d %d" % (a, a + sides, b + sides))
    count = len(profile) * sides
    lines.append("usemtl tentacle")
    for k in range(8):
        t = 2 * math.pi * (k + 0.5) / 8
        segments = 8
        for s_ in range(segments + 1):
            y = 0.62 - 0.75 * s_ / segments
            wave = 0.05 * math.sin(s_ * 1.3 + k)
            r = 0.3 - 0.12 * s_ / segments
            cx, cz = (r + wave) * math.cos(t), (r + wave) * math.sin(t)
            ox, oz = -0.025 * math.sin(t), 0.025 * math.cos(t)
            lines.append("v %.4f %.4f %.4f" % (cx - ox, y, cz - oz))
            lines.append("v %.4f %.4f %.4f" % (cx + ox, y, cz + oz))
        for s_ in range(segments):
            a = count + 2 * s_ + 1
            lines.append("f %d %d %d" % (a, a + 1, a + 3))
            lines.append("f %d %d %d" % (a, a + 3, a + 2))
        count += 2 * (segments + 1)
    write("jellyfish.obj", "\n".join(lines) + "\n")
    write("jellyfish.mtl", "newmtl bell\nKd 1.0 0.62 0.92\n\nnewmtl tentacle\nKd 0.95 0.75 1.0\n")


def obj_kelp():
    # A tall kelp card: one wide, four high, standing on y = 0, alpha cut-out.
    write("kelp.obj", "# kelp card (made by scripts/make-scene-assets.py)\nmtllib kelp.mtl\n"
          "usemtl blade\nv -0.5 0 0\nv 0.5 0 0\nv 0.5 4 0\nv -0.5 4 0\n"
          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n")
    write("kelp.mtl", "newmtl blade\nKd 0.8 1 0.7\nmap_Kd kelp.png\n")
    png("kelp.png", 32, 128, kelp)


def main():
    os.makedirs(OUT, exist_ok=True)
    obj_floor()
    obj_rock()
    obj_card()
    obj_fish()
    png("crate.png", 16, 16, checker)
    gltf_box("crate", "crate.png", (1.0, 1.0, 1.0))  # texture beside the file
    gltf_box("chest", png(None, 16, 16, star), (0.9, 0.8, 1.0))  # embedded texture
    gltf_box("lantern", png(None, 16, 16, checker), (0.6, 0.9, 1.0), animated=True)
    obj_ship()
    obj_jellyfish()
    obj_kelp()
    png("ocean_panorama.png", 512, 256, panorama)


if __name__ == "__main__":
    main()
