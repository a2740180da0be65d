#!/usr/bin/env python3
"""Writes a seeded corpus of small hostile mesh files into DIR, one or more per attack and
format load_mesh reads (and a few it refuses to read): huge and wrapping counts, counts with
trailing characters, list counts beyond their type, indices out of range and negative,
truncations at many offsets, deep nesting, external references. Every file is malformed:
hostile_meshes_test.py expects `trackphys info` to refuse each one (issue 19).

Usage: make_hostile_meshes.py DIR
"""

import json
import random
import struct
import sys
from pathlib import Path

SEED = 1919

PLY_HEAD = ("ply\nformat ascii 1.0\nelement vertex {v}\nproperty float x\nproperty float y\n"
            "property float z\nelement face {f}\nproperty list {count} int vertex_indices\n"
            "end_header\n")
PLY_VERTICES = "0 0 0\n1 0 0\n0 0 1\n1 0 1\n"
OBJ = "o road\nv 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nvt 0 0\nvn 0 1 0\nf 1/1/1 2/1/1 3/1/1\n"
OFF = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 0 1\n1 0 1\n3 0 1 2\n3 1 3 2\n"
AC_HEAD = ('AC3Db\nMATERIAL "" rgb 1 1 1 amb 1 1 1 emis 0 0 0 spec 0 0 0 shi 1 trans 0\n'
           "OBJECT world\nkids 1\nOBJECT poly\nname \"road\"\nnumvert 4\n0 0 0\n1 0 0\n0 0 1\n"
           "1 0 1\n")
STL = ("solid road\nfacet normal 0 1 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\n"
       "endloop\nendfacet\nendsolid road\n")


def ac_surface(flags, refs):
    lines = [f"numsurf 1\nSURF {flags}\nmat 0\nrefs {len(refs)}"]
    lines += [f"{r} 0 0" for r in refs]
    return "\n".join(lines) + "\nkids 0\n"


def binary_ply(indices):
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n").encode()
    body = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 0, 1)
    return head + body + struct.pack("<B", len(indices)) + struct.pack(f"<{len(indices)}i", *indices)


def binary_stl(count, triangles):
    data = b"hostile binary STL".ljust(80, b" ") + struct.pack("<I", count)
    for _ in range(triangles):
        data += struct.pack("<12fH", 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0)
    return data


def gltf(buffer_uri="data:application/octet-stream;base64," + "A" * 48, byte_length=36,
         accessor=None, nodes=None, extra=None):
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": buffer_uri, "byteLength": byte_length}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [accessor or {"bufferView": 0, "componentType": 5126, "count": 3,
                                   "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": nodes if nodes is not None else [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
    }
    doc.update(extra or {})
    return json.dumps(doc)


def glb(doc, binary):
    body = doc.encode() + b" " * (-len(doc) % 4)
    binary += b"\0" * (-len(binary) % 4)
    out = struct.pack("<I4s", len(body), b"JSON") + body + struct.pack("<I4s", len(binary), b"BIN\0")
    return struct.pack("<4sII", b"glTF", 2, 12 + len(out) + len(binary)) + out + binary


def truncations(rng, data, low, high, count):
    """count distinct cut lengths in [low, high]."""
    return sorted(rng.sample(range(low, high + 1), min(count, high - low + 1)))


def corpus(rng):
    files = {}
    # PLY: counts, list counts, indices, truncations, header.
    valid_ply = PLY_HEAD.format(v=4, f=2, count="uchar") + PLY_VERTICES + "3 0 1 2\n3 1 3 2\n"
    files["ply_count_40_digits.ply"] = PLY_HEAD.format(v="9" * 40, f=1, count="uchar") + PLY_VERTICES
    files["ply_count_wraps_2_32.ply"] = PLY_HEAD.format(v=2**32 + 3, f=1, count="uchar") + PLY_VERTICES
    files["ply_count_beyond_file.ply"] = PLY_HEAD.format(v=4, f=3000000, count="uchar") + PLY_VERTICES
    files["ply_count_trailing.ply"] = PLY_HEAD.format(v="4abc", f=1, count="uchar") + PLY_VERTICES
    files["ply_list_40_digits.ply"] = (PLY_HEAD.format(v=4, f=1, count="uchar") + PLY_VERTICES +
                                       "9" * 40 + " 0 1 2\n")
    files["ply_list_beyond_uchar.ply"] = (PLY_HEAD.format(v=4, f=1, count="uchar") + PLY_VERTICES +
                                          "300 0 1 2\n")
    files["ply_list_negative.ply"] = (PLY_HEAD.format(v=4, f=1, count="int") + PLY_VERTICES +
                                      "-3 0 1 2\n")
    files["ply_index_high.ply"] = PLY_HEAD.format(v=4, f=1, count="uchar") + PLY_VERTICES + "3 0 1 4\n"
    files["ply_index_negative.ply"] = PLY_HEAD.format(v=4, f=1, count="uchar") + PLY_VERTICES + "3 0 -1 2\n"
    files["ply_face_of_no_index.ply"] = PLY_HEAD.format(v=4, f=1, count="uchar") + PLY_VERTICES + "0\n"
    files["ply_no_end_header.ply"] = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
    files["ply_nul_in_header.ply"] = "ply\nformat ascii 1.0\ncomment a\0\0end_header\n0 0 0\n"
    # assimp writes a later vertex or face element into the array sized by the first.
    second_vertices = "element vertex 10\nproperty float x\nproperty float y\nproperty float z\n"
    files["ply_second_vertex_element.ply"] = (
        PLY_HEAD.format(v=4, f=1, count="uchar").replace("element face", second_vertices + "element face") +
        PLY_VERTICES + "0 0 0\n" * 10 + "3 0 1 2\n")
    files["ply_strips_then_faces.ply"] = (
        PLY_HEAD.format(v=4, f=3, count="uchar").replace(
            "element face", "element tristrips 1\nproperty list int int vertex_indices\nelement face") +
        PLY_VERTICES + "40 " + " ".join(str(i % 4) for i in range(40)) + "\n" + "3 0 1 2\n" * 3)
    files["ply_binary_index_high.ply"] = binary_ply([0, 1, 3])
    files["ply_binary_index_negative.ply"] = binary_ply([0, -7, 2])
    for cut in truncations(rng, valid_ply, 1, len(valid_ply) - 2, 6):
        files[f"ply_ascii_cut_{cut}.ply"] = valid_ply[:cut]
    valid_binary = binary_ply([0, 1, 2])
    for cut in truncations(rng, valid_binary, 1, len(valid_binary) - 1, 6):
        files[f"ply_binary_cut_{cut}.ply"] = valid_binary[:cut]
    # STL
    files["stl_binary_count_beyond_size.stl"] = binary_stl(1000000, 1)
    files["stl_binary_count_wraps.stl"] = binary_stl(0xffffffff, 2)
    files["stl_four_vertices.stl"] = STL.replace("vertex 0 0 1\n", "vertex 0 0 1\nvertex 1 1 1\n")
    files["stl_bad_number.stl"] = STL.replace("vertex 1 0 0", "vertex 1 0 0x")
    valid_binary_stl = binary_stl(2, 2)
    for cut in truncations(rng, valid_binary_stl, 1, len(valid_binary_stl) - 1, 5):
        files[f"stl_binary_cut_{cut}.stl"] = valid_binary_stl[:cut]
    for cut in truncations(rng, STL, 1, STL.index("endsolid") - 1, 5):
        files[f"stl_ascii_cut_{cut}.stl"] = STL[:cut]
    # OBJ
    files["obj_index_high.obj"] = OBJ + "f 1 2 5\n"
    files["obj_index_negative_beyond.obj"] = OBJ + "f -1 -2 -5\n"
    files["obj_index_zero.obj"] = OBJ + "f 0 1 2\n"
    files["obj_index_wraps_2_32.obj"] = OBJ + f"f 1 2 {2**32 + 1}\n"
    files["obj_index_trailing.obj"] = OBJ + "f 1 2 3x\n"
    files["obj_texcoord_high.obj"] = OBJ + "f 1/9 2/1 3/1\n"
    files["obj_normal_high.obj"] = OBJ + "f 1//9 2//1 3//1\n"
    files["obj_40_digit_index.obj"] = OBJ + "f 1 2 " + "9" * 40 + "\n"
    for cut in truncations(rng, OBJ, 1, OBJ.index("f 1/1/1") - 1, 5):
        files[f"obj_cut_{cut}.obj"] = OBJ[:cut]
    # OFF
    files["off_count_30_digits.off"] = "OFF\n" + "6" * 30 + " 1 0\n0 0 0\n"
    files["off_count_wraps_2_32.off"] = "OFF\n4294967300 1 0\n0 0 0\n"
    files["off_count_beyond_file.off"] = "OFF\n4 90000000 0\n" + OFF[10:]
    files["off_index_high.off"] = OFF.replace("3 1 3 2", "3 1 4 2")
    files["off_index_negative.off"] = OFF.replace("3 1 3 2", "3 1 -3 2")
    files["off_face_count_beyond_line.off"] = OFF.replace("3 1 3 2", "9 1 3 2")
    for cut in truncations(rng, OFF, 1, len(OFF) - 2, 5):
        files[f"off_cut_{cut}.off"] = OFF[:cut]
    # AC3D
    valid_ac = AC_HEAD + ac_surface("0x10", [0, 1, 2])
    files["ac_strip_one_reference.ac"] = AC_HEAD + ac_surface("0x14", [0])
    # Two triangles, then a strip of one reference: assimp's face count wraps to one, it
    # writes two (the heap corruption of issue 19).
    files["ac_strip_wraps_face_count.ac"] = (
        AC_HEAD + "numsurf 3\nSURF 0x10\nmat 0\nrefs 3\n0 0 0\n1 0 0\n2 0 0\n"
        "SURF 0x10\nmat 0\nrefs 3\n1 0 0\n3 0 0\n2 0 0\nSURF 0x14\nmat 0\nrefs 1\n3 0 0\nkids 0\n")
    files["ac_index_high.ac"] = AC_HEAD + ac_surface("0x10", [0, 1, 4])
    files["ac_index_negative.ac"] = AC_HEAD + ac_surface("0x10", [0, -1, 2])
    files["ac_numvert_huge.ac"] = "AC3Db\nOBJECT poly\nnumvert 4000000000\n0 0 0\n"
    files["ac_numvert_wraps_2_32.ac"] = "AC3Db\nOBJECT poly\nnumvert 4294967297\n0 0 0\n"
    files["ac_numsurf_huge.ac"] = AC_HEAD + "numsurf 99999999\nSURF 0x10\n"
    files["ac_kids_huge.ac"] = "AC3Db\nOBJECT world\nkids 4294967295\n"
    files["ac_refs_trailing.ac"] = AC_HEAD + ac_surface("0x10", [0, 1, 2]).replace("refs 3", "refs 3z")
    files["ac_nested_100000.ac"] = "AC3Db\n" + "OBJECT group\nkids 1\n" * 100000
    files["ac_data_beyond_file.ac"] = "AC3Db\nOBJECT poly\ndata 1000000\nabc\n"
    for cut in truncations(rng, valid_ac, 1, len(valid_ac) - 2, 6):
        files[f"ac_cut_{cut}.ac"] = valid_ac[:cut]
    # glTF: references, accessors, nodes, JSON.
    files["gltf_buffer_etc_passwd.gltf"] = gltf("/etc/passwd")
    files["gltf_buffer_dotdot.gltf"] = gltf("../" * 12 + "etc/passwd")
    files["gltf_buffer_file_url.gltf"] = gltf("file:///etc/passwd")
    files["gltf_buffer_http.gltf"] = gltf("http://127.0.0.1:9/mesh.bin")
    files["gltf_buffer_data_no_base64.gltf"] = gltf("data:application/octet-stream,AAAA")
    files["gltf_buffer_data_bad_chars.gltf"] = gltf("data:application/octet-stream;base64,A*==")
    files["gltf_buffer_data_short.gltf"] = gltf("data:application/octet-stream;base64,AAAA")
    files["gltf_sparse_without_indices.gltf"] = gltf(accessor={
        "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
        "sparse": {"count": 2, "values": {"bufferView": 0}}})
    files["gltf_count_huge.gltf"] = gltf(accessor={"bufferView": 0, "componentType": 5126,
                                                   "count": 2**31, "type": "VEC3"})
    files["gltf_count_wraps_2_32.gltf"] = gltf(accessor={"bufferView": 0, "componentType": 5126,
                                                         "count": 2**32 + 3, "type": "VEC3"})
    files["gltf_offset_huge.gltf"] = gltf(accessor={"bufferView": 0, "componentType": 5126,
                                                    "count": 3, "type": "VEC3",
                                                    "byteOffset": 2**40})
    files["gltf_index_negative.gltf"] = gltf(nodes=[{"mesh": -1}])
    files["gltf_node_cycle.gltf"] = gltf(nodes=[{"mesh": 0, "children": [1]}, {"children": [0]}])
    files["gltf_nodes_nested_5000.gltf"] = gltf(
        nodes=[{"mesh": 0, "children": [1]}] + [{"children": [i + 1]} for i in range(1, 4999)] + [{}])
    files["gltf_json_nested_100000.gltf"] = "[" * 100000 + "]" * 100000
    # assimp 5.2 reads a skin's inverse bind matrices without looking: none crashed it
    # (SIGSEGV), too few for its joints it read past.
    files["gltf_skin_without_matrices.gltf"] = gltf(
        nodes=[{"mesh": 0, "skin": 0}], extra={"skins": [{"joints": [0]}]})
    files["gltf_skin_short_of_matrices.gltf"] = gltf(
        nodes=[{"mesh": 0, "skin": 0}, {}],
        extra={"skins": [{"joints": [0, 1], "inverseBindMatrices": 0}]})
    valid_gltf = gltf()
    for cut in truncations(rng, valid_gltf, 1, len(valid_gltf) - 1, 5):
        files[f"gltf_cut_{cut}.gltf"] = valid_gltf[:cut]
    # GLB
    doc_no_uri = json.loads(gltf())  # its buffer is the BIN chunk
    del doc_no_uri["buffers"][0]["uri"]
    valid_glb = glb(json.dumps(doc_no_uri), b"\0" * 36)
    files["glb_length_wrong.glb"] = valid_glb[:8] + struct.pack("<I", 2**31) + valid_glb[12:]
    files["glb_json_chunk_huge.glb"] = valid_glb[:12] + struct.pack("<I", 2**31) + valid_glb[16:]
    files["glb_bin_too_short.glb"] = glb(json.dumps(doc_no_uri), b"\0" * 8)
    files["glb_buffer_etc_passwd.glb"] = glb(gltf("/etc/passwd"), b"")
    for cut in truncations(rng, valid_glb, 1, len(valid_glb) - 1, 6):
        files[f"glb_cut_{cut}.glb"] = valid_glb[:cut]
    # Formats trackphys does not read, whose assimp readers crashed or ran for minutes.
    for ext in ("fbx", "dae", "x", "zae", "3ds", "blend"):
        files[f"unread_format.{ext}"] = bytes(rng.randrange(256) for _ in range(300))
    return files


def main():
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for name, data in corpus(random.Random(SEED)).items():
        (out / name).write_bytes(data.encode() if isinstance(data, str) else data)


if __name__ == "__main__":
    main()
