#!/usr/bin/env python3
"""Writes a seeded set of valid mesh files, every format and variant load_mesh reads, into DIR.

mesh_import_golden_test loads each and compares what it gets with the hashes recorded in
mesh_import_golden.txt by the loader as it was before import was bounded (issue 19), so that
the strict checks in front of each reader provably refuse nothing a valid file holds (three
files recorded again since, when duplicate triangles began to be dropped).

Usage: make_valid_meshes.py DIR
"""

import base64
import json
import random
import struct
import sys
from pathlib import Path

SEED = 19


def grid(rng, n):
    """n points on a 1/8 m grid (exact in float32 and in decimal text), a bumpy sheet."""
    return [(rng.randint(-800, 800) / 8, rng.randint(-80, 80) / 8, rng.randint(-800, 800) / 8)
            for _ in range(n)]


def fan(n_vertices, n_faces, rng, sides=(3,)):
    """Faces of the given side counts over n_vertices vertices, no repeated corner."""
    faces = []
    for _ in range(n_faces):
        faces.append(rng.sample(range(n_vertices), rng.choice(sides)))
    return faces


def text(v):
    return " ".join(repr(c) for c in v)


def write_obj(out, rng):
    vs = grid(rng, 12)
    faces = fan(12, 10, rng, (3, 4))
    lines = ["# valid OBJ", "mtllib missing.mtl", "o road"]
    lines += ["v " + text(v) for v in vs[:8]]
    lines += ["vt 0 0", "vn 0 1 0", "usemtl asphalt"]
    lines += ["f " + " ".join(f"{i + 1}/1/1" for i in f) for f in faces[:5] if max(f) < 8]
    lines += ["o wall", "g side"]
    lines += ["v " + text(v) for v in vs[8:]]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces[5:]]
    lines += ["f -1 -2 -3", "l 1 2", "p 3"]
    (out / "mixed.obj").write_text("\n".join(lines) + "\n")
    pentagon = "v 0 0 0\nv 2 0 0\nv 3 0 1\nv 1 0 2\nv -1 0 1\nf 1 2 3 4 5\n"
    (out / "pentagon.obj").write_text(pentagon)


def ply_header(fmt, n_vertices, n_faces, coord, count_type, index_type, extra=""):
    return ("ply\nformat " + fmt + " 1.0\ncomment made by make_valid_meshes.py\n"
            f"element vertex {n_vertices}\nproperty {coord} x\nproperty {coord} y\n"
            f"property {coord} z\nproperty uchar red\n{extra}"
            f"element face {n_faces}\nproperty list {count_type} {index_type} vertex_indices\n"
            "end_header\n")


def write_ply(out, rng):
    vs = grid(rng, 10)
    faces = fan(10, 9, rng, (3, 4))
    body = "".join(text(v) + " 200\n" for v in vs)
    body += "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in faces)
    (out / "ascii.ply").write_text(ply_header("ascii", 10, 9, "float", "uchar", "int") + body)
    crlf = ply_header("ascii", 10, 9, "double", "uint8", "uint32").replace("\n", "\r\n")
    (out / "ascii_crlf.ply").write_bytes((crlf + body.replace("\n", "\r\n")).encode())
    for fmt, order in (("binary_little_endian", "<"), ("binary_big_endian", ">")):
        for coord, code in (("float", "f"), ("double", "d")):
            head = ply_header(fmt, 10, 9, coord, "uchar", "uint", "property short tag\n")
            data = b"".join(struct.pack(order + 3 * code + "Bh", *v, 7, -3) for v in vs)
            data += b"".join(struct.pack(order + "B" + len(f) * "I", len(f), *f) for f in faces)
            (out / f"{fmt}_{coord}.ply").write_bytes(head.encode() + data)


def write_stl(out, rng):
    tris = [grid(rng, 3) for _ in range(8)]
    lines = ["solid road"]
    for t in tris:
        lines += ["  facet normal 0 1 0", "    outer loop"]
        lines += ["      vertex " + text(v) for v in t]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid road")
    (out / "ascii.stl").write_text("\n".join(lines) + "\n")
    data = b"binary STL from make_valid_meshes.py".ljust(80, b" ")
    data += struct.pack("<I", len(tris))
    for t in tris:
        data += struct.pack("<3f", 0, 1, 0) + b"".join(struct.pack("<3f", *v) for v in t)
        data += b"\0\0"
    (out / "binary.stl").write_bytes(data)


def write_off(out, rng):
    vs = grid(rng, 9)
    faces = fan(9, 7, rng, (3, 4))
    lines = ["OFF", "# a comment", f"{len(vs)} {len(faces)} 0"]
    lines += [text(v) for v in vs]
    lines += [f"{len(f)} " + " ".join(map(str, f)) for f in faces]
    (out / "mixed.off").write_text("\n".join(lines) + "\n")


def ac_object(rng, name, depth, kids_left):
    vs = grid(rng, 6)
    faces = fan(6, 5, rng, (3, 4))
    lines = ["OBJECT poly", f'name "{name}"', f"loc {rng.randint(-9, 9)} 0.5 {rng.randint(-9, 9)}"]
    if depth % 2:
        lines.append("rot 0 0 1 0 1 0 -1 0 0")
    lines.append(f"numvert {len(vs)}")
    lines += [text(v) for v in vs]
    lines.append(f"numsurf {len(faces)}")
    for f in faces:
        lines += ["SURF 0x10", "mat 0", f"refs {len(f)}"]
        lines += [f"{i} 0.5 0.5" for i in f]
    kids = [ac_object(rng, f"{name}_{k}", depth + 1, kids_left - 1) for k in range(kids_left)]
    lines.append(f"kids {len(kids)}")
    for k in kids:
        lines += k
    return lines


def write_ac(out, rng):
    lines = ["AC3Db", 'MATERIAL "grey" rgb 0.5 0.5 0.5  amb 0.2 0.2 0.2  emis 0 0 0  '
             "spec 0.5 0.5 0.5  shi 10  trans 0", "OBJECT world", "kids 2"]
    lines += ac_object(rng, "road", 0, 2)
    lines += ac_object(rng, "wall", 0, 0)
    (out / "nested.ac").write_text("\n".join(lines) + "\n")


def gltf_parts(rng):
    """JSON and binary buffer of a two-node scene: a parent with TRS, a child with a matrix."""
    vs = grid(rng, 8)
    faces = fan(8, 6, rng)
    positions = b"".join(struct.pack("<3f", *v) for v in vs)
    indices = b"".join(struct.pack("<3H", *f) for f in faces)
    buffer = positions + indices
    lo = [min(v[k] for v in vs) for k in range(3)]
    hi = [max(v[k] for v in vs) for k in range(3)]
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"mesh": 0, "translation": [1, 2, 3], "rotation": [0, 0.6, 0, 0.8], "children": [1]},
            {"mesh": 0, "matrix": [2, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 5, 0, 0, 1]},
        ],
        "meshes": [{"name": "road", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(buffer)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(positions), "byteStride": 12},
            {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(vs), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5123, "count": 3 * len(faces), "type": "SCALAR"},
        ],
    }
    return doc, buffer


def write_gltf(out, rng):
    doc, buffer = gltf_parts(rng)
    doc["buffers"][0]["uri"] = "external.bin"
    (out / "external.bin").write_bytes(buffer)
    (out / "external.gltf").write_text(json.dumps(doc))
    doc, buffer = gltf_parts(rng)
    doc["buffers"][0]["uri"] = ("data:application/octet-stream;base64," +
                                base64.b64encode(buffer).decode())
    (out / "embedded.gltf").write_text(json.dumps(doc))
    doc, buffer = gltf_parts(rng)
    buffer += b"\0" * (-len(buffer) % 4)
    doc["buffers"][0]["byteLength"] = len(buffer)
    body = json.dumps(doc).encode()
    body += b" " * (-len(body) % 4)
    glb = struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(body) + 8 + len(buffer))
    glb += struct.pack("<I4s", len(body), b"JSON") + body
    glb += struct.pack("<I4s", len(buffer), b"BIN\0") + buffer
    (out / "binary.glb").write_bytes(glb)


def main():
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    rng = random.Random(SEED)
    for write in (write_obj, write_ply, write_stl, write_off, write_ac, write_gltf):
        write(out, rng)


if __name__ == "__main__":
    main()
