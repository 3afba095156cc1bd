#!/usr/bin/env python3
"""Writes room.gltf beside this script: a closed 6 x 3 x 5 m room lit by its own light.

The room (x -3..3, y 0..3, z -2.5..2.5, metres, +y up) is the built-in playground scene `room` in
spirit: a table with a box on it, a chair and a crate, under a 1.2 x 0.6 m ceiling panel 2 cm
below the ceiling, facing down. The panel is an EXT_lights_area "rect" light (size = its height
0.6, rect.aspect = width / height = 2) on a node at (0, 2.98, -0.6) turned -90 degrees about +x,
so that the node's -z (where the light faces) is world -y, its +x (the width) world +x and its +y
(the height) world -z. A glTF camera inside the room looks at the table.

The shell's faces point into the room (seen from inside); furniture boxes point outwards. One
embedded base64 buffer; Python's standard library only; the same bytes every run:

    python3 web/rooms/make_room.py        # rewrites web/rooms/room.gltf
"""

import base64
import json
import math
import os
import struct

ROOM_LO = (-3.0, 0.0, -2.5)
ROOM_HI = (3.0, 3.0, 2.5)
PANEL_CENTRE = (0.0, 2.98, -0.6)
PANEL_WIDTH, PANEL_HEIGHT = 1.2, 0.6


def quad(corners, normal):
    """A quad (counter-clockwise seen from the side `normal` points to) as (positions, normals, indices)."""
    return list(corners), [normal] * 4, [0, 1, 2, 0, 2, 3]


def box(lo, hi):
    """An axis-aligned box, 6 faces with their own vertices, normals outwards."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    faces = [
        ([(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)], (1, 0, 0)),
        ([(x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (x0, y0, z0)], (-1, 0, 0)),
        ([(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)], (0, 1, 0)),
        ([(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)], (0, -1, 0)),
        ([(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)], (0, 0, 1)),
        ([(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)], (0, 0, -1)),
    ]
    return merge([quad(c, n) for c, n in faces])


def merge(parts):
    positions, normals, indices = [], [], []
    for p, n, i in parts:
        base = len(positions)
        positions += p
        normals += n
        indices += [base + k for k in i]
    return positions, normals, indices


def room_floor():
    (x0, y0, z0), (x1, _, z1) = ROOM_LO, ROOM_HI
    return quad([(x0, y0, z1), (x1, y0, z1), (x1, y0, z0), (x0, y0, z0)], (0, 1, 0))


def room_walls_and_ceiling():
    (x0, y0, z0), (x1, y1, z1) = ROOM_LO, ROOM_HI
    return merge([
        quad([(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)], (0, -1, 0)),  # ceiling
        quad([(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)], (0, 0, 1)),   # back wall
        quad([(x1, y0, z1), (x0, y0, z1), (x0, y1, z1), (x1, y1, z1)], (0, 0, -1)),  # front wall
        quad([(x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1)], (1, 0, 0)),   # left wall
        quad([(x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0)], (-1, 0, 0)),  # right wall
    ])


def table(top, thickness, height, leg=0.06, inset=0.05):
    """A top of size `top` (x, z) whose upper face is at `height`, four legs; centred on the origin."""
    hx, hz = top[0] / 2, top[1] / 2
    parts = [box((-hx, height - thickness, -hz), (hx, height, hz))]
    for sx in (-1, 1):
        for sz in (-1, 1):
            cx, cz = sx * (hx - inset - leg / 2), sz * (hz - inset - leg / 2)
            parts.append(box((cx - leg / 2, 0.0, cz - leg / 2), (cx + leg / 2, height - thickness, cz + leg / 2)))
    return merge(parts)


def chair():
    """A 0.44 x 0.44 seat at 0.45 on four legs, a backrest up to 0.9 on its +z side; centred on the origin."""
    seat = table((0.44, 0.44), 0.04, 0.45, leg=0.04, inset=0.02)
    rest = box((-0.18, 0.45, 0.19), (0.18, 0.9, 0.22))
    return merge([seat, rest])


def look_rotation(eye, target):
    """The unit quaternion (x, y, z, w) turning a glTF camera (looking down -z, +y up) at `target`."""
    back = [e - t for e, t in zip(eye, target)]
    n = math.sqrt(sum(c * c for c in back))
    back = [c / n for c in back]
    right = [back[2], 0.0, -back[0]]  # (0, 1, 0) x back
    n = math.sqrt(sum(c * c for c in right))
    right = [c / n for c in right]
    up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
          back[0] * right[1] - back[1] * right[0]]
    m = [[right[0], up[0], back[0]], [right[1], up[1], back[1]], [right[2], up[2], back[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        q = [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    else:  # not reached for this camera; kept for other eyes
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0, 0.0, 0.0, (m[k][j] - m[j][k]) / s]
        q[i] = s / 4
        q[j] = (m[j][i] + m[i][j]) / s
        q[k] = (m[k][i] + m[i][k]) / s
    return [round(c, 7) for c in q]


def build():
    buffer = bytearray()
    accessors, views = [], []

    def add_view(data, target):
        while len(buffer) % 4:
            buffer.append(0)
        views.append({"buffer": 0, "byteOffset": len(buffer), "byteLength": len(data), "target": target})
        buffer.extend(data)
        return len(views) - 1

    def add_primitive(geometry, material):
        positions, normals, indices = geometry
        pos = add_view(b"".join(struct.pack("<3f", *p) for p in positions), 34962)
        lo = [min(p[a] for p in positions) for a in range(3)]
        hi = [max(p[a] for p in positions) for a in range(3)]
        # min/max as the float32 values stored
        lo = [struct.unpack("<f", struct.pack("<f", v))[0] for v in lo]
        hi = [struct.unpack("<f", struct.pack("<f", v))[0] for v in hi]
        accessors.append({"bufferView": pos, "componentType": 5126, "count": len(positions), "type": "VEC3",
                          "min": [round(v, 6) for v in lo], "max": [round(v, 6) for v in hi]})
        nrm = add_view(b"".join(struct.pack("<3f", *n) for n in normals), 34962)
        accessors.append({"bufferView": nrm, "componentType": 5126, "count": len(normals), "type": "VEC3"})
        idx = add_view(b"".join(struct.pack("<H", i) for i in indices), 34963)
        accessors.append({"bufferView": idx, "componentType": 5123, "count": len(indices), "type": "SCALAR"})
        n = len(accessors)
        return {"attributes": {"POSITION": n - 3, "NORMAL": n - 2}, "indices": n - 1, "material": material}

    def material(name, rgb):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0], "metallicFactor": 0.0,
                                                       "roughnessFactor": 0.9}}

    materials = [material("walls", (0.82, 0.82, 0.78)), material("floor", (0.55, 0.48, 0.4)),
                 material("wood", (0.5, 0.32, 0.18)), material("crate", (0.7, 0.6, 0.42))]
    meshes = [
        {"name": "shell", "primitives": [add_primitive(room_floor(), 1), add_primitive(room_walls_and_ceiling(), 0)]},
        {"name": "table", "primitives": [add_primitive(table((1.6, 0.8), 0.05, 0.75), 2)]},
        {"name": "box", "primitives": [add_primitive(box((-0.175, 0.0, -0.125), (0.175, 0.25, 0.125)), 3)]},
        {"name": "chair", "primitives": [add_primitive(chair(), 2)]},
        {"name": "crate", "primitives": [add_primitive(box((-0.275, 0.0, -0.3), (0.275, 0.45, 0.3)), 3)]},
    ]
    half = math.sqrt(0.5)
    table_at = [-0.4, 0.0, -1.2]
    eye, look_at = [0.9, 1.7, 2.3], [-0.4, 0.75, -1.2]
    nodes = [
        {"name": "shell", "mesh": 0},
        {"name": "table", "mesh": 1, "translation": table_at},
        # on the table top (0.75), turned 20 degrees about +y
        {"name": "box", "mesh": 2, "translation": [-0.7, 0.75, -1.3],
         "rotation": [0.0, round(math.sin(math.radians(10)), 7), 0.0, round(math.cos(math.radians(10)), 7)]},
        {"name": "chair", "mesh": 3, "translation": [-0.2, 0.0, -0.45]},
        {"name": "crate", "mesh": 4, "translation": [2.1, 0.0, -2.19]},  # 1 cm off the back wall
        # The light: -90 degrees about +x takes the node's -z (where it faces) to world -y.
        {"name": "ceiling panel", "translation": list(PANEL_CENTRE), "rotation": [-half, 0.0, 0.0, half],
         "extensions": {"EXT_lights_area": {"light": 0}}},
        {"name": "camera", "camera": 0, "translation": eye, "rotation": look_rotation(eye, look_at)},
    ]
    gltf = {
        "asset": {"version": "2.0", "generator": "penumbra web/rooms/make_room.py"},
        "extensionsUsed": ["EXT_lights_area"],
        "extensions": {"EXT_lights_area": {"lights": [{
            "name": "ceiling panel", "type": "rect", "color": [1.0, 0.96, 0.9], "intensity": 1000.0,
            "size": PANEL_HEIGHT, "rect": {"aspect": PANEL_WIDTH / PANEL_HEIGHT}}]}},
        "scene": 0,
        "scenes": [{"name": "room", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"name": "inside", "type": "perspective",
                     "perspective": {"yfov": round(math.radians(60), 7), "znear": 0.02, "zfar": 15.0}}],
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buffer)).decode("ascii")}],
    }
    return json.dumps(gltf, indent=1) + "\n"


if __name__ == "__main__":
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "room.gltf")
    with open(out, "w", encoding="ascii", newline="\n") as f:
        f.write(build())
    print("wrote", out)
