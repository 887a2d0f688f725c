#!/usr/bin/env python3
"""Writes the Cornell box of scenes/cornell.json as glTF 2.0: tests/data/cornell.gltf (with its
buffer in cornell.bin) and the same scene as one binary file, tests/data/cornell.glb; and the
scenes that load them, cornell_gltf.json and cornell_glb.json (camera, lights and solver block
as in scenes/cornell.json; one mesh surface "cornell").

One node per surface, named as the surface, its polygon triangulated (a convex polygon as a fan,
the ceiling's hole by joining it to the outer ring), units mm as in the JSON. The reflectance is
baseColorFactor; the light's exitance E comes back as pi x emissiveFactor x emissiveStrength
(KHR_materials_emissive_strength), glTF's emission being radiance as MTL Ke is. The tall block is
stored around its own origin under a parent node that moves it (translation and rotation), the
short block likewise under a node with a matrix, so that both kinds of node transform are used.

    python3 tests/data/cornell_gltf.py      # from anywhere; writes beside this script
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "scenes", "cornell.json")
# A polygon corner off the polygon's plane by more than this (mm) is refused.
PLANARITY_MM = 1e-6


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def newell_normal(ring):
    """The ring's area-weighted normal (right-hand rule)."""
    n = [0.0, 0.0, 0.0]
    for i, p in enumerate(ring):
        n = add(n, cross(p, ring[(i + 1) % len(ring)]))
    return n


def is_planar(ring, normal):
    """Every corner lies within PLANARITY_MM of the plane through the first with this normal."""
    return all(abs(dot(sub(q, ring[0]), normal)) <= PLANARITY_MM * math.sqrt(dot(normal, normal)) for q in ring)


def check_convex(ring, normal, name):
    """Every corner of the ring turns the same way as `normal`."""
    for i, p in enumerate(ring):
        q, r = ring[(i + 1) % len(ring)], ring[(i + 2) % len(ring)]
        if dot(cross(sub(q, p), sub(r, q)), normal) <= 0:
            raise SystemExit(f"{name}: not convex at corner {(i + 1) % len(ring)}: a fan would not cover it")


def corner_angle(p, q, r):
    """The angle at q between its edges to p and r."""
    u, v = sub(p, q), sub(r, q)
    return math.acos(max(-1.0, min(1.0, dot(u, v) / math.sqrt(dot(u, u) * dot(v, v)))))


def fan(ring, name):
    """A convex ring's triangles as a fan from its first corner (its winding kept). A non-planar
    quad (the classic data's left wall) is split along the diagonal a Delaunay triangulation takes,
    as the scene loader does: the one whose opposite corners' angles add up to less than pi."""
    normal = newell_normal(ring)
    check_convex(ring, normal, name)
    if not is_planar(ring, normal):
        if len(ring) != 4:
            raise SystemExit(f"{name}: a non-planar polygon of more than 4 corners")
        if corner_angle(ring[0], ring[1], ring[2]) + corner_angle(ring[2], ring[3], ring[0]) > math.pi:
            ring = ring[1:] + ring[:1]  # the other diagonal
    return [[ring[0], ring[i], ring[i + 1]] for i in range(1, len(ring) - 1)]


def angle_about(p, centre, normal, axis):
    """The angle of p about `centre` in the plane of `normal`, from `axis`."""
    d = sub(p, centre)
    return math.atan2(dot(cross(axis, d), normal) / math.sqrt(dot(normal, normal)), dot(axis, d))


def with_hole(outer, hole, name):
    """A convex ring with a convex hole of as many corners, as the quads joining corner i of each
    (the hole's corners matched to the outer's by their angle about the centre), two triangles each."""
    normal = newell_normal(outer)
    if dot(newell_normal(hole), normal) < 0:
        hole = hole[::-1]
    centre = [sum(p[i] for p in hole) / len(hole) for i in range(3)]
    axis = sub(outer[0], centre)
    start = min(range(len(hole)), key=lambda k: abs(angle_about(hole[k], centre, normal, axis)))
    hole = hole[start:] + hole[:start]
    triangles = []
    for i in range(len(outer)):
        j = (i + 1) % len(outer)
        quad = [outer[i], outer[j], hole[j], hole[i]]
        check_convex(quad, normal, f"{name} (quad {i + 1} around its hole)")
        if not is_planar(quad, normal):
            raise SystemExit(f"{name}: quad {i + 1} around its hole is not planar")
        triangles += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    return triangles


def triangles_of(surface):
    if len(surface.get("holes", [])) > 1:
        raise SystemExit(f"{surface['name']}: more than one hole")
    if surface.get("holes"):
        return with_hole(surface["polygon"], surface["holes"][0], surface["name"])
    return fan(surface["polygon"], surface["name"])


def rotation_y(quarter_turns):
    """The matrix (rows) of a rotation by quarter_turns x 90 degrees about +y, exact."""
    c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][quarter_turns % 4]
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def apply(m, p):
    return [dot(m[i], p) for i in range(3)]


def transposed(m):
    return [[m[j][i] for j in range(3)] for i in range(3)]


def block_centre(surfaces):
    """The centre of a block's bottom (its sides' lowest corners), rounded to 0.5 mm so that the
    corners relative to it, whole millimetres and halves, are exact in float."""
    corners = [p for s in surfaces for p in s["polygon"]]
    low = min(p[1] for p in corners)
    bottom = [p for p in corners if p[1] == low]
    return [round(2 * sum(p[i] for p in bottom) / len(bottom)) / 2 for i in range(3)]


def localised(triangles, centre, quarter_turns):
    """The triangles in the block's own frame: p_local = R^T (p - centre)."""
    back = transposed(rotation_y(quarter_turns))
    return [[apply(back, sub(p, centre)) for p in t] for t in triangles]


class Buffer:
    """The binary buffer, its views and accessors as they are added."""

    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def add(self, payload, target, accessor):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload), "target": target})
        self.data += payload
        accessor["bufferView"] = len(self.views) - 1
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def triangles(self, triangles):
        """Positions (float, shared corners once) and indices (unsigned short) of the triangles."""
        corners, index = [], []
        for t in triangles:
            for p in t:
                key = tuple(p)
                if key not in corners:
                    corners.append(key)
                index.append(corners.index(key))
        flat = [c for p in corners for c in p]
        lo = [min(p[i] for p in corners) for i in range(3)]
        hi = [max(p[i] for p in corners) for i in range(3)]
        position = self.add(struct.pack(f"<{len(flat)}f", *flat), 34962,
                            {"componentType": 5126, "count": len(corners), "type": "VEC3", "min": lo, "max": hi})
        indices = self.add(struct.pack(f"<{len(index)}H", *index), 34963,
                           {"componentType": 5123, "count": len(index), "type": "SCALAR"})
        return {"attributes": {"POSITION": position}, "indices": indices, "mode": 4}


def material_of(name, m):
    """A glTF material: reflectance as base colour; exitance E as pi x factor x strength."""
    out = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": m["reflectance"] + [1.0], "metallicFactor": 0.0,
                                                  "roughnessFactor": 1.0}}
    if "emission" in m:
        radiance = [e / math.pi for e in m["emission"]]
        strength = max(radiance)
        out["emissiveFactor"] = [r / strength for r in radiance]
        out["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
    return out


def block_parent(name, surfaces, quarter_turns, use_matrix):
    """The parent node of a block's surfaces (stored around its own origin, turned back by
    quarter_turns x 90 degrees about y), and its centre. Quarter turns and half millimetres keep
    every position exact in float, so that the blocks stand where the JSON has them to 1e-13 mm
    (float rounding of a general turn, ~1e-5 mm, moves the mesh near a block's foot enough to
    change the light shown at a point 9 mm from its corner by tens of per cent)."""
    centre = block_centre(surfaces)
    node = {"name": name, "children": []}
    if use_matrix:
        r = rotation_y(quarter_turns)  # column-major 4x4
        node["matrix"] = [r[0][0], r[1][0], r[2][0], 0, r[0][1], r[1][1], r[2][1], 0,
                          r[0][2], r[1][2], r[2][2], 0, centre[0], centre[1], centre[2], 1]
    else:
        half = quarter_turns * math.pi / 4
        node["translation"] = centre
        node["rotation"] = [0.0, math.sin(half), 0.0, math.cos(half)]
    return node, centre


# The blocks' parent nodes: quarter turns about y, and whether given as a matrix (else as
# translation and rotation).
BLOCKS = {"tall_block": (1, False), "short_block": (-1, True)}


def build():
    scene = json.load(open(SCENE))
    names = list(scene["materials"])
    gltf = {"asset": {"version": "2.0", "generator": "tests/data/cornell_gltf.py from scenes/cornell.json"},
            "extensionsUsed": ["KHR_materials_emissive_strength"], "scene": 0, "scenes": [{"nodes": []}],
            "nodes": [], "meshes": [], "materials": [material_of(n, scene["materials"][n]) for n in names]}
    buffer = Buffer()
    parents = {}
    for s in scene["surfaces"]:
        triangles = triangles_of(s)
        block = next((b for b in BLOCKS if s["name"].startswith(b)), None)
        if block and block not in parents:
            turns, use_matrix = BLOCKS[block]
            node, centre = block_parent(block, [t for t in scene["surfaces"] if t["name"].startswith(block)], turns,
                                        use_matrix)
            gltf["nodes"].append(node)
            gltf["scenes"][0]["nodes"].append(len(gltf["nodes"]) - 1)
            parents[block] = (node, centre, turns)
        if block:
            triangles = localised(triangles, parents[block][1], parents[block][2])
        primitive = buffer.triangles(triangles)
        primitive["material"] = names.index(s["material"])
        gltf["meshes"].append({"name": s["name"], "primitives": [primitive]})
        gltf["nodes"].append({"name": s["name"], "mesh": len(gltf["meshes"]) - 1})
        if block:
            parents[block][0]["children"].append(len(gltf["nodes"]) - 1)
        else:
            gltf["scenes"][0]["nodes"].append(len(gltf["nodes"]) - 1)
    gltf["accessors"], gltf["bufferViews"] = buffer.accessors, buffer.views
    return gltf, bytes(buffer.data)


def glb(gltf, data):
    """The binary container: header, JSON chunk (space-padded), BIN chunk (zero-padded)."""
    gltf = dict(gltf, buffers=[{"byteLength": len(data)}])
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def scene_using(mesh):
    """scenes/cornell.json with its surfaces replaced by the one mesh file."""
    scene = json.load(open(SCENE))
    scene["materials"] = {}
    scene["surfaces"] = [{"name": "cornell", "mesh": mesh}]
    return scene


def main():
    gltf, data = build()
    for mesh, name in (("cornell.gltf", "cornell_gltf.json"), ("cornell.glb", "cornell_glb.json")):
        with open(os.path.join(HERE, name), "w") as f:
            json.dump(scene_using(mesh), f, indent=2)
            f.write("\n")
    with open(os.path.join(HERE, "cornell.bin"), "wb") as f:
        f.write(data)
    with open(os.path.join(HERE, "cornell.gltf"), "w") as f:
        json.dump(dict(gltf, buffers=[{"uri": "cornell.bin", "byteLength": len(data)}]), f, indent=1)
        f.write("\n")
    with open(os.path.join(HERE, "cornell.glb"), "wb") as f:
        f.write(glb(gltf, data))


if __name__ == "__main__":
    main()
