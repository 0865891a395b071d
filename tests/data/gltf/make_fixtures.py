#!/usr/bin/env python3
"""Writes the small glTF fixtures in this folder (run: python3 make_fixtures.py).

The fixtures are committed; this script only documents how each was made and regenerates them
if one needs changing. Valid fixtures exercise one loader feature each; malformed ones are
named after the problem they contain, and framework/scene/tests/gltf_loader_test.cpp checks each error names
the file and the problem. Buffers are embedded as base64 data URIs so each fixture is one file,
except where the point is an external URI.
"""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963
UBYTE, USHORT, UINT, FLOAT = 5121, 5123, 5125, 5126


def floats(values):
    return struct.pack("<%df" % len(values), *values)


def pad4(data):
    return data + b"\0" * (-len(data) % 4)


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


class Builder:
    """Accumulates one buffer and the bufferViews/accessors that describe it."""

    def __init__(self):
        self.data = b""
        self.views = []
        self.accessors = []

    def view(self, payload, target=None, stride=None):
        self.data = pad4(self.data)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if target:
            v["target"] = target
        if stride:
            v["byteStride"] = stride
        self.data += payload
        self.views.append(v)
        return len(self.views) - 1

    def accessor(self, view, ctype, count, atype, **extra):
        a = {"bufferView": view, "componentType": ctype, "count": count, "type": atype}
        a.update(extra)
        self.accessors.append(a)
        return len(self.accessors) - 1

    def gltf(self, meshes, nodes, scene_nodes, uri=None, **extra):
        g = {
            "asset": {"version": "2.0", "generator": "make_fixtures.py"},
            "scene": 0,
            "scenes": [{"nodes": scene_nodes}],
            "nodes": nodes,
            "meshes": meshes,
            "accessors": self.accessors,
            "bufferViews": self.views,
            "buffers": [{"byteLength": len(pad4(self.data)), "uri": uri or data_uri(pad4(self.data))}],
        }
        g.update(extra)
        return g


TRI_POS = [0, 0, 0, 1, 0, 0, 0, 1, 0]
TRI_NRM = [0, 0, 1] * 3
QUAD_POS = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
QUAD_NRM = [0, 0, 1] * 4
QUAD_IDX = [0, 1, 2, 0, 2, 3]


def triangle(b, indices=None, index_type=USHORT):
    """A unit right triangle in the XY plane facing +Z; returns the primitive."""
    pos = b.view(floats(TRI_POS), ARRAY_BUFFER)
    nrm = b.view(floats(TRI_NRM), ARRAY_BUFFER)
    prim = {
        "attributes": {
            "POSITION": b.accessor(pos, FLOAT, 3, "VEC3", min=[0, 0, 0], max=[1, 1, 0]),
            "NORMAL": b.accessor(nrm, FLOAT, 3, "VEC3"),
        }
    }
    if indices is not None:
        fmt = {UBYTE: "B", USHORT: "H", UINT: "I"}[index_type]
        idx = b.view(struct.pack("<%d%s" % (len(indices), fmt), *indices), ELEMENT_ARRAY_BUFFER)
        prim["indices"] = b.accessor(idx, index_type, len(indices), "SCALAR")
    return prim


def write_json(name, doc, compact=False):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(doc, f, indent=None if compact else 1, sort_keys=True)
        f.write("\n")


def write_text(name, text):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(text)


def glb(doc, bin_data):
    """A GLB container: header, JSON chunk (space padded), BIN chunk (zero padded)."""
    js = json.dumps(doc, sort_keys=True).encode()
    js += b" " * (-len(js) % 4)
    bin_data = pad4(bin_data)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js
    if bin_data:
        body += struct.pack("<II", len(bin_data), 0x004E4942) + bin_data
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def simple(name, mutate=None, indices=(0, 1, 2), index_type=USHORT, compact=False, **extra):
    """A one-triangle scene; `mutate(doc)` breaks it in one specific way."""
    b = Builder()
    prim = triangle(b, list(indices) if indices is not None else None, index_type)
    doc = b.gltf([{"name": "tri", "primitives": [prim]}], [{"mesh": 0, "name": "tri"}], [0], **extra)
    if mutate:
        mutate(doc)
    write_json(name, doc, compact)
    return doc, b


def quad_with_index_type(name, index_type):
    b = Builder()
    pos = b.view(floats(QUAD_POS), ARRAY_BUFFER)
    nrm = b.view(floats(QUAD_NRM), ARRAY_BUFFER)
    fmt = {UBYTE: "B", USHORT: "H", UINT: "I"}[index_type]
    # Two junk indices first, skipped by the accessor's byteOffset, to check offsets are honoured.
    size = struct.calcsize(fmt)
    idx = b.view(struct.pack("<%d%s" % (8, fmt), 9, 9, *QUAD_IDX), ELEMENT_ARRAY_BUFFER)
    prim = {
        "attributes": {
            "POSITION": b.accessor(pos, FLOAT, 4, "VEC3", min=[0, 0, 0], max=[1, 1, 0]),
            "NORMAL": b.accessor(nrm, FLOAT, 4, "VEC3"),
        },
        "indices": b.accessor(idx, index_type, 6, "SCALAR", byteOffset=2 * size),
    }
    write_json(name, b.gltf([{"name": "quad", "primitives": [prim]}], [{"mesh": 0, "name": "quad"}], [0]))


def node_transforms():
    """Parent scale 2 -> child translation (1,0,0) -> grandchild given as a matrix
    (translation (0,0,3)); a spot light on the child, turned to shine along +X."""
    b = Builder()
    prim = triangle(b, [0, 1, 2])
    s = 0.7071067811865476  # rotation of -90 degrees about Y: local -Z becomes world +X
    nodes = [
        {"name": "parent", "scale": [2, 2, 2], "children": [1]},
        {"name": "child", "translation": [1, 0, 0], "mesh": 0, "children": [2, 3]},
        {"name": "grandchild", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1], "mesh": 0},
        {"name": "spot", "rotation": [0, -s, 0, s], "extensions": {"KHR_lights_punctual": {"light": 0}}},
    ]
    lights = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 3, "range": 10,
         "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}]}}
    doc = b.gltf([{"name": "tri", "primitives": [prim]}], nodes, [0],
                 extensions=lights, extensionsUsed=["KHR_lights_punctual"])
    write_json("node_transforms.gltf", doc)


def sparse_doc(sparse_indices):
    """POSITION with no bufferView (all zeros) and a sparse override of two vertices."""
    b = Builder()
    idx = b.view(struct.pack("<2H", *sparse_indices))
    val = b.view(floats([1, 0, 0, 0, 1, 0]))
    nrm = b.view(floats(TRI_NRM), ARRAY_BUFFER)
    b.accessors.append({
        "componentType": FLOAT, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
        "sparse": {"count": 2, "indices": {"bufferView": idx, "componentType": USHORT},
                   "values": {"bufferView": val}}})
    prim = {"attributes": {"POSITION": 0, "NORMAL": b.accessor(nrm, FLOAT, 3, "VEC3")}}
    return b.gltf([{"name": "tri", "primitives": [prim]}], [{"mesh": 0}], [0])


def sparse():
    write_json("sparse.gltf", sparse_doc((1, 2)))
    write_json("sparse_index_out_of_range.gltf", sparse_doc((1, 7)))
    doc = sparse_doc((1, 2))
    doc["accessors"][0]["count"] = 5000000  # all zeros but two: a few bytes asking for 60 MB
    write_json("unbacked_huge_count.gltf", doc)


def many_instances():
    """A 1048575-vertex mesh (all zeros but one real triangle, no normals, not indexed) drawn by
    21 nodes at x = 0..20: more vertex transforms than the loader spends on exact bounds, so
    the bounds come from each instance's transformed box."""
    b = Builder()
    idx = b.view(struct.pack("<2I", 1, 2))
    val = b.view(floats([1, 0, 0, 0, 1, 0]))
    b.accessors.append({
        "componentType": FLOAT, "count": 1048575, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
        "sparse": {"count": 2, "indices": {"bufferView": idx, "componentType": UINT},
                   "values": {"bufferView": val}}})
    prim = {"attributes": {"POSITION": 0}}
    nodes = [{"mesh": 0, "translation": [i, 0, 0]} for i in range(21)]
    write_json("many_instances.gltf", b.gltf([{"name": "big", "primitives": [prim]}], nodes, list(range(21))))


def texcoords_normalized():
    """TEXCOORD_0 as normalized unsigned bytes in a view with byteStride 4 (2 bytes of UV and
    2 bytes of filler per vertex)."""
    b = Builder()
    pos = b.view(floats(TRI_POS), ARRAY_BUFFER)
    uv = b.view(struct.pack("<12B", 0, 0, 7, 7, 255, 0, 7, 7, 0, 255, 7, 7), ARRAY_BUFFER, stride=4)
    prim = {"attributes": {
        "POSITION": b.accessor(pos, FLOAT, 3, "VEC3", min=[0, 0, 0], max=[1, 1, 0]),
        "TEXCOORD_0": b.accessor(uv, UBYTE, 3, "VEC2", normalized=True)}}
    write_json("texcoords_normalized.gltf", b.gltf([{"name": "tri", "primitives": [prim]}], [{"mesh": 0}], [0]))


def modes_and_camera():
    """One triangle-list primitive and one POINTS primitive (skipped); a camera without zfar
    (infinite) looking down -Z from (0, 0, 5); no `scene`, so scene 0 is used."""
    b = Builder()
    tri = triangle(b, [0, 1, 2])
    points = dict(tri)
    points["mode"] = 0
    doc = b.gltf([{"name": "mixed", "primitives": [tri, points]}],
                 [{"mesh": 0, "name": "mixed"}, {"camera": 0, "translation": [0, 0, 5], "name": "cam"}],
                 [0, 1], cameras=[{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.05}}])
    del doc["scene"]
    write_json("modes_and_camera.gltf", doc)


def tangent_quads():
    """Three quads facing +Z, side by side, each a mesh of its own, seen by a camera at (0, 0, 6):
    "right_handed" (x -2..-0.8) with TANGENT (1, 0, 0, +1) and u along +x; "no_tangents"
    (x -0.6..0.6) with the same texture coordinates and no TANGENT; "mirrored" (x 0.8..2) with u
    running along -x and TANGENT (-1, 0, 0, -1). In all three v runs down the quad (glTF's
    convention), so the bitangent cross(n, t.xyz) * w points up (+y). The debug view's test
    (framework/render/tests/debug_view_test.cpp) reads them."""
    b = Builder()
    meshes, nodes = [], []
    for name, x0, x1, mirrored, tangents in (("right_handed", -2.0, -0.8, False, True),
                                             ("no_tangents", -0.6, 0.6, False, False),
                                             ("mirrored", 0.8, 2.0, True, True)):
        pos = b.view(floats([x0, -0.8, 0, x1, -0.8, 0, x1, 0.8, 0, x0, 0.8, 0]), ARRAY_BUFFER)
        nrm = b.view(floats(QUAD_NRM), ARRAY_BUFFER)
        u = [1, 0, 0, 1] if mirrored else [0, 1, 1, 0]
        uv = b.view(floats([u[0], 1, u[1], 1, u[2], 0, u[3], 0]), ARRAY_BUFFER)
        idx = b.view(struct.pack("<6H", *QUAD_IDX), ELEMENT_ARRAY_BUFFER)
        attributes = {
            "POSITION": b.accessor(pos, FLOAT, 4, "VEC3", min=[x0, -0.8, 0], max=[x1, 0.8, 0]),
            "NORMAL": b.accessor(nrm, FLOAT, 4, "VEC3"),
            "TEXCOORD_0": b.accessor(uv, FLOAT, 4, "VEC2"),
        }
        if tangents:
            t = [-1, 0, 0, -1] if mirrored else [1, 0, 0, 1]
            attributes["TANGENT"] = b.accessor(b.view(floats(t * 4), ARRAY_BUFFER), FLOAT, 4, "VEC4")
        prim = {"attributes": attributes, "indices": b.accessor(idx, USHORT, 6, "SCALAR")}
        meshes.append({"name": name, "primitives": [prim]})
        nodes.append({"mesh": len(nodes), "name": name})
    nodes.append({"camera": 0, "translation": [0, 0, 6], "name": "camera"})
    doc = b.gltf(meshes, nodes, [0, 1, 2, 3],
                 cameras=[{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 20}}])
    write_json("tangent_quads.gltf", doc)


def triangle_glb():
    b = Builder()
    prim = triangle(b, [0, 1, 2])
    doc = b.gltf([{"name": "tri", "primitives": [prim]}], [{"mesh": 0}], [0])
    doc["buffers"] = [{"byteLength": len(pad4(b.data))}]
    data = glb(doc, b.data)
    write_text("triangle.glb", data)
    write_text("truncated.glb", data[: len(data) - 40])
    # The BIN chunk claims 8 bytes more than the file holds: tinygltf 2.7.0 alone would read them.
    bin_at = 12 + 8 + struct.unpack_from("<I", data, 12)[0]
    bad = bytearray(data)
    struct.pack_into("<I", bad, bin_at, struct.unpack_from("<I", data, bin_at)[0] + 8)
    write_text("glb_bin_chunk_overrun.glb", bytes(bad))
    # A GLB whose only buffer has byteLength 0 (tinygltf 2.7.0 throws on it).
    doc0 = json.loads(json.dumps(doc))
    doc0["buffers"] = [{"byteLength": 0}]
    write_text("glb_empty_buffer.glb", glb(doc0, b.data))
    write_text("not_glb.glb", b"this is not a binary glTF file\n")


def main():
    # Valid fixtures.
    quad_with_index_type("indices_ubyte.gltf", UBYTE)
    quad_with_index_type("indices_ushort.gltf", USHORT)
    quad_with_index_type("indices_uint.gltf", UINT)
    simple("non_indexed.gltf", indices=None)
    node_transforms()
    tangent_quads()
    sparse()
    many_instances()
    texcoords_normalized()
    modes_and_camera()
    triangle_glb()

    # Malformed fixtures, one problem each.
    def grow_count(doc):
        doc["accessors"][0]["count"] = 4  # 4 * 12 bytes from a 36-byte view
    simple("accessor_out_of_range.gltf", grow_count)

    def view_past_buffer(doc):
        doc["bufferViews"][1]["byteLength"] = 400
    simple("bad_buffer_view.gltf", view_past_buffer)

    def view_overflow(doc):
        doc["bufferViews"][1]["byteOffset"] = 16
        doc["bufferViews"][1]["byteLength"] = 18446744073709551600
    simple("buffer_view_overflow.gltf", view_overflow)

    def offset_overflow(doc):
        doc["accessors"][0]["byteOffset"] = 18446744073709551600
    simple("accessor_offset_overflow.gltf", offset_overflow)

    def huge_count(doc):
        doc["accessors"][0]["count"] = 4000000000
    simple("huge_count.gltf", huge_count)

    def missing_bin(doc):
        doc["buffers"][0]["uri"] = "missing_bin.bin"
    simple("missing_bin.gltf", missing_bin)

    def escape(doc):
        doc["buffers"][0]["uri"] = "../secret.bin"
    simple("uri_escapes_folder.gltf", escape)

    def escape_encoded(doc):
        doc["buffers"][0]["uri"] = "%2e%2e/%2e%2e/secret.bin"
    simple("uri_percent_escape.gltf", escape_encoded)

    def absolute(doc):
        doc["buffers"][0]["uri"] = "/etc/passwd"
    simple("uri_absolute.gltf", absolute)

    def wrong_type(doc):
        doc["accessors"][0]["type"] = "VEC2"
    simple("wrong_type_position.gltf", wrong_type)

    def float_indices(doc):
        doc["accessors"][2]["componentType"] = FLOAT
        doc["accessors"][2]["count"] = 1
    simple("wrong_type_indices.gltf", float_indices)

    simple("index_out_of_range.gltf", indices=(0, 1, 7))

    def no_position(doc):
        del doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
    simple("missing_position.gltf", no_position)

    def bad_stride(doc):
        doc["bufferViews"][0]["byteStride"] = 8
    simple("bad_stride.gltf", bad_stride)

    def cycle(doc):
        doc["nodes"] = [{"name": "a", "children": [1]}, {"name": "b", "children": [0], "mesh": 0}]
    simple("node_cycle.gltf", cycle)

    def bad_child(doc):
        doc["nodes"][0]["children"] = [99]
    simple("bad_node_child.gltf", bad_child)

    def bad_mesh(doc):
        doc["nodes"][0]["mesh"] = 5
    simple("bad_mesh_index.gltf", bad_mesh)

    def bad_light(doc):
        doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 5}}})
        doc["scenes"][0]["nodes"].append(1)
    simple("bad_light_index.gltf", bad_light)

    def basisu(doc):
        doc["extensionsUsed"] = ["KHR_texture_basisu"]
        doc["extensionsRequired"] = ["KHR_texture_basisu"]
    simple("required_extension.gltf", basisu)

    def bad_matrix(doc):
        doc["nodes"][0]["matrix"] = [1, 0, 0]
    simple("bad_matrix.gltf", bad_matrix)

    def bad_scene(doc):
        doc["scene"] = 3
    simple("bad_default_scene.gltf", bad_scene)

    def short_base64(doc):
        doc["buffers"][0]["byteLength"] = doc["buffers"][0]["byteLength"] + 100
    simple("data_uri_too_short.gltf", short_base64)

    def deep_extras(doc):
        nested = []
        for _ in range(300):  # past the loader's limit of 128, within Python's recursion limit
            nested = [nested]
        doc["extras"] = nested
    simple("json_too_deep.gltf", deep_extras, compact=True)

    write_text("not_json.gltf", b"this is not JSON {\n")
    write_text("empty.gltf", b"")
    write_text("json_not_gltf.gltf", b"[1, 2, 3]\n")


if __name__ == "__main__":
    main()
