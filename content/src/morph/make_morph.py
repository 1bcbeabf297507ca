#!/usr/bin/env python3
"""Writes morph.gltf + morph.bin: morph targets animated by a clip, for the GPU morph path
(shaders/skinning/skinning.comp) and its tests — the shared assets hold no morphing model.

Two 32 x 32-vertex sheets, 1 m tall, facing +Z, sharing three morph targets (POSITION and NORMAL
displacements, glTF 2.0 §3.7.2.2):
  0 "bulge": z += 0.25·exp(−r²/0.04) around the sheet's centre
  1 "wave":  z += 0.08·sin(2π·2x)
  2 "lean":  x += 0.2·y²
Target normals are the displaced surface's normals minus the base normal (finite differences).
  node "sheet": the morphing sheet alone (mesh "sheet"), at x = −0.7
  node "arm":   the same targets on a 0.4 m-wide strip skinned to two joints ("root" at x = 0.7,
                "elbow" 0.5 m above it; weights blend over y in [0.35, 0.65]): morph, then skin
Clip "Wave" (2 s, LINEAR): the three weights of both meshes through five keys, the elbow
rotating 0° → 45° → 0° about +Z. Deterministic; the output is committed. Licence: CC0 1.0.
Run: /usr/bin/python3 make_morph.py
"""
import json, math, struct

import numpy as np

N = 32
s = np.linspace(0.0, 1.0, N)
gx, gy = np.meshgrid(s, s, indexing="xy")  # gx along x, gy along y; row j = y


def surface(width, x0):
    x = x0 + (gx - 0.5) * width
    y = gy.copy()
    return np.stack([x, y, np.zeros_like(x)], axis=-1)


def normals(p):
    du = np.gradient(p, axis=1)
    dv = np.gradient(p, axis=0)
    n = np.cross(du, dv)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def targets(base, x0):
    cx, cy = x0, 0.5
    r2 = (base[..., 0] - cx) ** 2 + (base[..., 1] - cy) ** 2
    d0 = np.zeros_like(base)
    d0[..., 2] = 0.25 * np.exp(-r2 / 0.04)
    d1 = np.zeros_like(base)
    d1[..., 2] = 0.08 * np.sin(2 * math.pi * 2 * (base[..., 0] - x0))
    d2 = np.zeros_like(base)
    d2[..., 0] = 0.2 * base[..., 1] ** 2
    n0 = normals(base)
    return [(d, normals(base + d) - n0) for d in (d0, d1, d2)]


blob = bytearray()
views, accessors = [], []


def add(arr, comp, typ, target=None, minmax=False):
    arr = np.ascontiguousarray(arr)
    raw = arr.astype({5126: "<f4", 5123: "<u2", 5125: "<u4"}[comp]).tobytes()
    while len(blob) % 4:
        blob.append(0)
    view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(raw)}
    if target:
        view["target"] = target
    views.append(view)
    blob.extend(raw)
    count = arr.shape[0]
    acc = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": typ}
    if minmax:
        acc["min"] = [float(v) for v in arr.min(axis=0)]
        acc["max"] = [float(v) for v in arr.max(axis=0)]
    accessors.append(acc)
    return len(accessors) - 1


idx = []
for j in range(N - 1):
    for i in range(N - 1):
        a, b, c, d = j * N + i, j * N + i + 1, (j + 1) * N + i + 1, (j + 1) * N + i
        idx += [a, b, c, a, c, d]  # counter-clockwise seen from +Z
indices = add(np.array(idx, dtype=np.uint32), 5125, "SCALAR", 34963)
uv = np.stack([gx, 1.0 - gy], axis=-1).reshape(-1, 2)
uvs = add(uv.astype(np.float32), 5126, "VEC2", 34962)


def primitive(width, x0, material, skin=False):
    base = surface(width, x0)
    attrs = {"POSITION": add(base.reshape(-1, 3).astype(np.float32), 5126, "VEC3", 34962, True),
             "NORMAL": add(normals(base).reshape(-1, 3).astype(np.float32), 5126, "VEC3", 34962),
             "TEXCOORD_0": uvs}
    if skin:
        t = np.clip((gy.reshape(-1) - 0.35) / 0.3, 0.0, 1.0)
        w = t * t * (3 - 2 * t)  # smoothstep: the elbow's share
        joints = np.zeros((N * N, 4), dtype=np.uint16)
        joints[:, 1] = 1
        weights = np.zeros((N * N, 4), dtype=np.float32)
        weights[:, 0] = 1.0 - w
        weights[:, 1] = w
        attrs["JOINTS_0"] = add(joints, 5123, "VEC4", 34962)
        attrs["WEIGHTS_0"] = add(weights, 5126, "VEC4", 34962)
    tg = [{"POSITION": add(d.reshape(-1, 3).astype(np.float32), 5126, "VEC3", 34962, True),
           "NORMAL": add(n.reshape(-1, 3).astype(np.float32), 5126, "VEC3", 34962)} for d, n in targets(base, x0)]
    return {"attributes": attrs, "indices": indices, "material": material, "targets": tg}


sheet = primitive(1.0, 0.0, 0)
arm = primitive(0.4, 0.7, 1, skin=True)

times = np.array([0.0, 0.5, 1.0, 1.5, 2.0], dtype=np.float32)
keys = np.array([[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [0, 0.5, 1], [0, 0, 0]], dtype=np.float32)
t_in = add(times.reshape(-1, 1), 5126, "SCALAR", minmax=True)
w_out = add(keys.reshape(-1, 1), 5126, "SCALAR")
r_times = np.array([0.0, 1.0, 2.0], dtype=np.float32)
r_in = add(r_times.reshape(-1, 1), 5126, "SCALAR", minmax=True)
h = math.radians(45) / 2
rot = np.array([[0, 0, 0, 1], [0, 0, math.sin(h), math.cos(h)], [0, 0, 0, 1]], dtype=np.float32)
r_out = add(rot, 5126, "VEC4")
ibm = np.stack([np.eye(4), np.eye(4)]).astype(np.float32)
ibm[0][:3, 3] = [-0.7, 0.0, 0.0]
ibm[1][:3, 3] = [-0.7, -0.5, 0.0]
ibm_acc = add(np.stack([m.T.reshape(-1) for m in ibm]), 5126, "MAT4")  # column-major

names = {"targetNames": ["bulge", "wave", "lean"]}
gltf = {
    "asset": {"version": "2.0", "generator": "bounce content/src/morph/make_morph.py"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [
        {"name": "sheet", "mesh": 0, "translation": [-0.7, 0, 0]},
        {"name": "arm", "mesh": 1, "skin": 0},
        {"name": "root", "translation": [0.7, 0, 0], "children": [3]},
        {"name": "elbow", "translation": [0, 0.5, 0]},
    ],
    "meshes": [{"name": "sheet", "primitives": [sheet], "weights": [0, 0, 0], "extras": names},
               {"name": "arm", "primitives": [arm], "weights": [0, 0, 0], "extras": names}],
    "skins": [{"name": "arm", "joints": [2, 3], "inverseBindMatrices": ibm_acc, "skeleton": 2}],
    "animations": [{"name": "Wave",
                    "samplers": [{"input": t_in, "output": w_out, "interpolation": "LINEAR"},
                                 {"input": r_in, "output": r_out, "interpolation": "LINEAR"}],
                    "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}},
                                 {"sampler": 0, "target": {"node": 1, "path": "weights"}},
                                 {"sampler": 1, "target": {"node": 3, "path": "rotation"}}]}],
    "materials": [{"name": "sheet", "doubleSided": True,
                   "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.3, 1], "metallicFactor": 0, "roughnessFactor": 0.8}},
                  {"name": "arm", "doubleSided": True,
                   "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.5, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 0.8}}],
    "buffers": [{"byteLength": len(blob), "uri": "morph.bin"}],
    "bufferViews": views,
    "accessors": accessors,
}
with open("morph.bin", "wb") as f:
    f.write(bytes(blob))
with open("morph.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
