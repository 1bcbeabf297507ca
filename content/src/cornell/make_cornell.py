#!/usr/bin/env python3
"""Writes cornell.gltf + cornell.bin: the Cornell box from the published measurements
(graphics.cornell.edu/online/box/data.html), closed with a front wall as in the DNRT paper's
tests 1-2 ("closed off ... to maximize the amount of indirect light").

Coordinates: the published data is in millimetres with x to the left, y up, z into the box and the
camera at (278, 273, -800). We convert to glTF metres, centre the box on x/z and turn it 180 degrees
about +Y so the camera looks down -Z:  x' = -(x - 278) / 1000,  y' = y / 1000,  z' = -(z - 279.6) / 1000.
The floor is at y = 0, the ceiling at y = 0.5488, the back wall at z = -0.2796, the front wall at
z = +0.2796. The red wall is on the viewer's left (x' < 0), the green wall on the right.

Reflectances: the published data gives spectra; we use the RGB values commonly derived from them
(as in Mitsuba's and pbrt's cbox scenes): white (0.725, 0.71, 0.68), red (0.63, 0.065, 0.05),
green (0.14, 0.45, 0.091). The area light is replaced by a point light in the level (DNRT paper).
Run: /usr/bin/python3 make_cornell.py  (deterministic; the output is committed).
"""
import json, struct, math, os

WHITE, RED, GREEN = (0.725, 0.71, 0.68), (0.63, 0.065, 0.05), (0.14, 0.45, 0.091)

# Published quads (mm). Walls face the box interior, blocks face outwards.
FLOOR = [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]
CEILING = [(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]
BACK = [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]
FRONT = [(552.8, 0, 0), (0, 0, 0), (0, 548.8, 0), (556, 548.8, 0)]
RIGHT = [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]          # green
LEFT = [(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]  # red
SHORT = [
    [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)],
    [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)],
    [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)],
    [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)],
    [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)],
]
TALL = [
    [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)],
    [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)],
    [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)],
    [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)],
    [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)],
]


def to_gltf(p):
    x, y, z = p
    return (-(x - 278.0) / 1000.0, y / 1000.0, -(z - 279.6) / 1000.0)


def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm(a):
    l = math.sqrt(dot(a, a))
    return tuple(x / l for x in a)


def quad_mesh(quads, inward_to=None, outward_from=None):
    """Two triangles per quad, flat normals, CCW about the normal (glTF front face)."""
    pos, nrm, uv, idx = [], [], [], []
    for q in quads:
        q = [to_gltf(p) for p in q]
        n = norm(cross(sub(q[1], q[0]), sub(q[2], q[0])))
        c = tuple(sum(p[i] for p in q) / 4 for i in range(3))
        want = sub(inward_to, c) if inward_to else sub(c, outward_from)
        if dot(n, want) < 0:
            q, n = q[::-1], tuple(-x for x in n)
        base = len(pos)
        pos += q
        nrm += [n] * 4
        uv += [(0, 0), (1, 0), (1, 1), (0, 1)]
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def centre(quads):
    pts = [to_gltf(p) for q in quads for p in q]
    return tuple(sum(p[i] for p in pts) / len(pts) for i in range(3))


def main():
    box_centre = (0.0, 0.2744, 0.0)
    parts = [
        ("floor", [FLOOR], 0, dict(inward_to=box_centre)),
        ("ceiling", [CEILING], 0, dict(inward_to=box_centre)),
        ("back_wall", [BACK], 0, dict(inward_to=box_centre)),
        ("front_wall", [FRONT], 0, dict(inward_to=box_centre)),
        ("left_wall_red", [LEFT], 1, dict(inward_to=box_centre)),
        ("right_wall_green", [RIGHT], 2, dict(inward_to=box_centre)),
        ("short_block", SHORT, 0, dict(outward_from=centre(SHORT))),
        ("tall_block", TALL, 0, dict(outward_from=centre(TALL))),
    ]
    blob = bytearray()
    views, accessors, meshes, nodes = [], [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    def add_accessor(values, comps, ctype, kind, target, minmax=False):
        fmt = {5126: "f", 5125: "I"}[ctype]
        flat = [v for t in values for v in (t if isinstance(t, tuple) else (t,))]
        view = add_view(struct.pack("<%d%s" % (len(flat), fmt), *flat), target)
        a = {"bufferView": view, "componentType": ctype, "count": len(values), "type": kind}
        if minmax:
            a["min"] = [min(v[i] for v in values) for i in range(comps)]
            a["max"] = [max(v[i] for v in values) for i in range(comps)]
        accessors.append(a)
        return len(accessors) - 1

    for name, quads, mat, orient in parts:
        pos, nrm, uv, idx = quad_mesh(quads, **orient)
        prim = {
            "attributes": {
                "POSITION": add_accessor(pos, 3, 5126, "VEC3", 34962, minmax=True),
                "NORMAL": add_accessor(nrm, 3, 5126, "VEC3", 34962),
                "TEXCOORD_0": add_accessor(uv, 2, 5126, "VEC2", 34962),
            },
            "indices": add_accessor(idx, 1, 5125, "SCALAR", 34963),
            "material": mat,
        }
        meshes.append({"name": name, "primitives": [prim]})
        nodes.append({"name": name, "mesh": len(meshes) - 1})

    def material(name, rgb):
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0],
                                                        "metallicFactor": 0.0, "roughnessFactor": 1.0}}

    gltf = {
        "asset": {"version": "2.0", "generator": "bounce content/src/cornell/make_cornell.py",
                  "copyright": "CC0 1.0; geometry from the Cornell box data (Cornell University Program of Computer Graphics)"},
        "scene": 0,
        "scenes": [{"name": "cornell", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [material("white", WHITE), material("red", RED), material("green", GREEN)],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": "cornell.bin", "byteLength": len(blob)}],
    }
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "cornell.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(here, "cornell.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
