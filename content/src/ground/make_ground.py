#!/usr/bin/env python3
"""Writes ground.gltf: a 1 m x 1 m square in the XZ plane at y = 0, facing +Y, centred on the
origin, mid-grey (albedo 0.5) — the ground plane of the level `bounce` makes for a glTF file
(game/viewer_level.cpp scales it to the asset). The buffer is embedded as a data: URI.
Run: /usr/bin/python3 make_ground.py  (deterministic; the output is committed). Licence: CC0.
"""
import base64, json, struct

POS = [(-0.5, 0, -0.5), (-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 0, -0.5)]
NRM = [(0, 1, 0)] * 4
UV = [(0, 0), (0, 1), (1, 1), (1, 0)]
IDX = [0, 1, 2, 0, 2, 3]  # counter-clockwise seen from +Y

data = b"".join(struct.pack("<3f", *p) for p in POS) + b"".join(struct.pack("<3f", *n) for n in NRM)
data += b"".join(struct.pack("<2f", *t) for t in UV) + struct.pack("<6H", *IDX)
gltf = {
    "asset": {"version": "2.0", "generator": "bounce content/src/ground/make_ground.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "ground", "mesh": 0}],
    "meshes": [{"name": "ground", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                                  "indices": 3, "material": 0}]}],
    "materials": [{"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                                              "metallicFactor": 0, "roughnessFactor": 1}}],
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 32}, {"buffer": 0, "byteOffset": 128, "byteLength": 12}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, 0, -0.5], "max": [0.5, 0, 0.5]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ],
}
with open("ground.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
