#!/usr/bin/env python3
"""Writes a glTF with N distinct boxes (each its own size and material): N albedo keys, for
benchmarking the albedo baker (`twinlight bake --scene OUT --db X.db --force`).
Usage: make_many_keys_scene.py OUT.gltf [N=1000]"""
import base64, json, random, struct, sys

out = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
random.seed(1)
buf = bytearray()
meshes, nodes, accessors, views, materials = [], [], [], [], []
faces = []
for axis in range(3):
    for sign in (-1, 1):
        nrm, u, v = [0, 0, 0], [0, 0, 0], [0, 0, 0]
        nrm[axis], u[(axis + 1) % 3], v[(axis + 2) % 3] = sign, 1, 1
        faces.append((nrm, u, v))
for i in range(n):
    size = [0.2 + random.random() for _ in range(3)]
    pos, idx = [], []
    for nrm, u, v in faces:
        base = len(pos)
        for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append([(nrm[k] + u[k] * cu + v[k] * cv) * 0.5 * size[k] for k in range(3)])
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    offset = len(buf)
    for p in pos:
        buf += struct.pack("<3f", *p)
    views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(pos) * 12})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(pos), "type": "VEC3",
                      "min": [min(p[k] for p in pos) for k in range(3)], "max": [max(p[k] for p in pos) for k in range(3)]})
    offset = len(buf)
    for j in idx:
        buf += struct.pack("<H", j)
    while len(buf) % 4:
        buf += b"\0"
    views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(idx) * 2})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": len(idx), "type": "SCALAR"})
    materials.append({"name": f"m{i}", "pbrMetallicRoughness": {
        "baseColorFactor": [random.random(), random.random(), random.random(), 1],
        "metallicFactor": random.choice([0, 1]), "roughnessFactor": 0.5}})
    meshes.append({"name": f"box{i}", "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                     "indices": len(accessors) - 1, "material": i}]})
    nodes.append({"name": f"box{i}", "mesh": i, "translation": [(i % 32) * 2.0, 0, (i // 32) * 2.0]})
gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(n))}], "nodes": nodes,
        "meshes": meshes, "materials": materials, "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}]}
with open(out, "w") as f:
    json.dump(gltf, f)
print(f"wrote {out}: {n} distinct boxes")
