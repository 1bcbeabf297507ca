#!/usr/bin/python3
"""Writes quad.gltf: one unit square in the XZ plane (x, z in [-0.5, 0.5], y = 0), normal +Y,
counter-clockwise seen from +Y, with a white diffuse material. The analytic render tests scale it
into a large floor and a small occluder. Run: /usr/bin/python3 make_quad.py (deterministic)."""
import base64, json, struct

positions = [(-0.5, 0, -0.5), (-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 0, -0.5)]
normals = [(0, 1, 0)] * 4
uvs = [(0, 0), (0, 1), (1, 1), (1, 0)]
indices = [0, 1, 2, 0, 2, 3]

data = b"".join(struct.pack("<3f", *p) for p in positions)
data += b"".join(struct.pack("<3f", *n) for n in normals)
data += b"".join(struct.pack("<2f", *t) for t in uvs)
data += struct.pack("<6H", *indices) + b"\0\0"  # pad to 4 bytes

gltf = {
    "asset": {"version": "2.0", "generator": "bounce tests/data/render/make_quad.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "Quad", "mesh": 0}],
    "meshes": [{"name": "Quad", "primitives": [{
        "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
    "materials": [{"name": "White", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 1}}],
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
        {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
        {"buffer": 0, "byteOffset": 96, "byteLength": 32, "target": 34962},
        {"buffer": 0, "byteOffset": 128, "byteLength": 12, "target": 34963},
    ],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
         "min": [-0.5, 0, -0.5], "max": [0.5, 0, 0.5]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5123, "count": 6, "type": "SCALAR"},
    ],
}
with open("quad.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
