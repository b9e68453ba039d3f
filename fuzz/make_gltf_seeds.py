#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_gltf_animation (docs/fuzzing.md): small
glTF files of every kind read_gltf_animation() reads. Run from the checkout:
    python3 fuzz/make_gltf_seeds.py
"""
import base64
import json
import os
import struct

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus", "fuzz_gltf_animation")


class Doc:
    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}, "bufferViews": [], "accessors": []}
        self.bin = b""

    def view(self, data):
        self.bin += b"\0" * (-len(self.bin) % 4)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def floats(self, values, type_, width, **extra):
        acc = {"bufferView": self.view(struct.pack("<%df" % len(values), *values)), "componentType": 5126,
               "count": len(values) // width, "type": type_}
        acc.update(extra)
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def indices(self, values, fmt="H", ctype=5123):
        acc = {"bufferView": self.view(struct.pack("<%d%s" % (len(values), fmt), *values)), "componentType": ctype,
               "count": len(values), "type": "SCALAR"}
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def glb(self):
        self.bin += b"\0" * (-len(self.bin) % 4)
        d = dict(self.doc, buffers=[{"byteLength": len(self.bin)}])
        j = json.dumps(d).encode()
        j += b" " * (-len(j) % 4)
        return (struct.pack("<III", 0x46546C67, 2, 28 + len(j) + len(self.bin)) + struct.pack("<II", len(j), 0x4E4F534A)
                + j + struct.pack("<II", len(self.bin), 0x004E4942) + self.bin)

    def gltf(self):
        uri = "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()
        return json.dumps(dict(self.doc, buffers=[{"byteLength": len(self.bin), "uri": uri}])).encode()


def morph():
    """What write_animation_glb writes: base + one target per later frame, LINEAR one-hot weights."""
    d = Doc()
    pos = d.floats([0, 0, 0, 10, 0, 0, 0, 10, 0, 10, 10, 1], "VEC3", 3, min=[0, 0, 0], max=[10, 10, 1])
    idx = d.indices([0, 1, 2, 2, 1, 3], "I", 5125)
    t1 = d.floats([0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4], "VEC3", 3)
    t2 = d.floats([1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0], "VEC3", 3)
    times = d.floats([0, 1 / 30, 2 / 30], "SCALAR", 1)
    w = d.floats([0, 0, 1, 0, 0, 1], "SCALAR", 1)
    d.doc["meshes"] = [{"name": "body", "weights": [0, 0], "primitives": [
        {"attributes": {"POSITION": pos}, "indices": idx, "mode": 4, "targets": [{"POSITION": t1}, {"POSITION": t2}]}]}]
    d.doc["nodes"] = [{"name": "body", "mesh": 0}]
    d.doc["scenes"] = [{"nodes": [0]}]
    d.doc["scene"] = 0
    d.doc["animations"] = [{"name": "motion", "samplers": [{"input": times, "output": w, "interpolation": "LINEAR"}],
                            "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]
    return d


def rigid():
    """A strip on a child node; the parent turns (LINEAR), the child steps and scales (CUBICSPLINE); a sparse target."""
    d = Doc()
    pos = d.floats([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], "VEC3", 3)
    idx = d.indices([0, 1, 2, 3], "B", 5121)
    sparse_i = d.view(struct.pack("<H", 3))
    sparse_v = d.view(struct.pack("<3f", 0, 0, 2))
    d.doc["accessors"].append({"componentType": 5126, "count": 4, "type": "VEC3", "sparse": {
        "count": 1, "indices": {"bufferView": sparse_i, "componentType": 5123}, "values": {"bufferView": sparse_v}}})
    target = len(d.doc["accessors"]) - 1
    times = d.floats([0, 0.5, 1], "SCALAR", 1)
    rot = d.indices([0, 0, 0, 32767, 0, 0, 12540, 30273, 0, 0, 23170, 23170], "h", 5122)
    d.doc["accessors"][rot].update(type="VEC4", count=3, normalized=True)
    step = d.floats([0, 0, 0, 0, 0, 5, 0, 0, 5], "VEC3", 3)
    cubic = d.floats([0, 0, 0, 1, 1, 1, 0, 0, 0] * 3, "VEC3", 3)
    weights = d.floats([0, 1, 0.5], "SCALAR", 1)
    d.doc["meshes"] = [{"name": "strip", "primitives": [
        {"attributes": {"POSITION": pos}, "indices": idx, "mode": 5, "targets": [{"POSITION": target}]}]}]
    d.doc["nodes"] = [{"name": "root", "children": [1], "translation": [100, 0, 0], "rotation": [0, 0, 0, 1]},
                      {"name": "leaf", "mesh": 0, "scale": [1, 1, 1]},
                      {"name": "other", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1], "mesh": 0}]
    d.doc["scenes"] = [{"nodes": [0, 2]}]
    d.doc["animations"] = [{"name": "turn", "samplers": [
        {"input": times, "output": rot},
        {"input": times, "output": step, "interpolation": "STEP"},
        {"input": times, "output": cubic, "interpolation": "CUBICSPLINE"},
        {"input": times, "output": weights}],
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "rotation"}},
                     {"sampler": 1, "target": {"node": 1, "path": "translation"}},
                     {"sampler": 2, "target": {"node": 1, "path": "scale"}},
                     {"sampler": 3, "target": {"node": 2, "path": "weights"}}]}]
    return d


def skinned():
    """A skinned strip: two joint sets (the same joint in both), float weights, joints listed out of node order,
    inverse bind matrices; the hips move (LINEAR), the spine turns; the mesh node's translation is to be ignored."""
    d = Doc()
    pos = d.floats([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], "VEC3", 3)
    idx = d.indices([0, 1, 2, 3], "B", 5121)
    j0 = d.indices([1, 0, 0, 0] * 3 + [0, 1, 0, 0], "B", 5121)
    d.doc["accessors"][j0].update(type="VEC4", count=4)
    j1 = d.indices([0, 0, 0, 0] * 3 + [1, 0, 0, 0], "H", 5123)
    d.doc["accessors"][j1].update(type="VEC4", count=4)
    w0 = d.floats([1, 0, 0, 0] * 3 + [0.25, 0.25, 0, 0], "VEC4", 4)
    w1 = d.floats([0, 0, 0, 0] * 3 + [0.25, 0.25, 0, 0], "VEC4", 4)
    ibm = d.floats([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1,
                    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "MAT4", 16)
    times = d.floats([0, 1], "SCALAR", 1)
    move = d.floats([0, 0, 0, 10, 0, 0], "VEC3", 3)
    h = 0.5 ** 0.5
    turn = d.floats([0, 0, 0, 1, 0, 0, h, h], "VEC4", 4)
    d.doc["meshes"] = [{"name": "torso", "primitives": [
        {"attributes": {"POSITION": pos, "JOINTS_0": j0, "WEIGHTS_0": w0, "JOINTS_1": j1, "WEIGHTS_1": w1},
         "indices": idx, "mode": 5}]}]
    d.doc["nodes"] = [{"name": "hips", "children": [1]},
                      {"name": "spine", "translation": [0, 0, 1]},
                      {"name": "skinned", "mesh": 0, "skin": 0, "translation": [50, 0, 0]}]
    d.doc["skins"] = [{"joints": [1, 0], "inverseBindMatrices": ibm, "skeleton": 0}]
    d.doc["scenes"] = [{"nodes": [0, 2]}]
    d.doc["animations"] = [{"name": "twist", "samplers": [{"input": times, "output": move},
                                                          {"input": times, "output": turn}],
                            "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}},
                                         {"sampler": 1, "target": {"node": 1, "path": "rotation"}}]}]
    return d


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    for name, data in [("morph_targets.glb", morph().glb()), ("rigid_hierarchy.glb", rigid().glb()),
                       ("morph_targets_data_uri.gltf", morph().gltf()), ("skinned.glb", skinned().glb())]:
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(data)
