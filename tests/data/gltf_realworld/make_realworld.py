#!/usr/bin/env python3
"""Writes the "real-world" glTF files in this folder (run: python3 make_realworld.py).

Each file reproduces one way scenes exported by Blender, Sketchfab or the Khronos samples differ
from the bundled ones (framework/scene/tests/gltf_realworld_test.cpp names what each must do: load and render
like its plain twin, or be refused with a given message). All are written by this script, or by
the Debian-packaged `draco_transcoder` and `gltfpack` from files it writes, so they are the
project's own (LICENSE.md). Buffers are embedded data URIs, so each .gltf is one file.
"""
import base64
import json
import math
import os
import shutil
import struct
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
BYTE, UBYTE, SHORT, USHORT, UINT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126
POINTS, LINES, TRIANGLES, STRIP, FAN = 0, 1, 4, 5, 6


def pad4(data):
    return data + b"\0" * (-len(data) % 4)


class Doc:
    """One glTF document with one buffer, built up view by view."""

    def __init__(self):
        self.data = b""
        self.g = {"asset": {"version": "2.0", "generator": "make_realworld.py"}, "scene": 0,
                  "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "accessors": [],
                  "bufferViews": []}

    def view(self, payload, target=None, stride=None):
        self.data = pad4(self.data)
        v = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if target:
            v["target"] = target
        if stride:
            v["byteStride"] = stride
        self.data += payload
        self.g["bufferViews"].append(v)
        return len(self.g["bufferViews"]) - 1

    def accessor(self, view, ctype, count, atype, **extra):
        a = {"componentType": ctype, "count": count, "type": atype}
        if view is not None:
            a["bufferView"] = view
        a.update(extra)
        self.g["accessors"].append(a)
        return len(self.g["accessors"]) - 1

    def floats(self, values, atype, target=ARRAY_BUFFER, **extra):
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}[atype]
        if atype == "VEC3" and "min" not in extra:
            extra["min"] = [min(values[i::3]) for i in range(3)]
            extra["max"] = [max(values[i::3]) for i in range(3)]
        v = self.view(struct.pack("<%df" % len(values), *values), target)
        return self.accessor(v, FLOAT, len(values) // n, atype, **extra)

    def indices(self, idx):
        v = self.view(struct.pack("<%dH" % len(idx), *idx), ELEMENT_ARRAY_BUFFER)
        return self.accessor(v, USHORT, len(idx), "SCALAR")

    def mesh(self, name, primitives):
        self.g["meshes"].append({"name": name, "primitives": primitives})
        return len(self.g["meshes"]) - 1

    def node(self, root=True, **fields):
        self.g["nodes"].append(fields)
        i = len(self.g["nodes"]) - 1
        if root:
            self.g["scenes"][0]["nodes"].append(i)
        return i

    def write(self, name, glb=False):
        self.g["buffers"] = [{"byteLength": len(pad4(self.data))}]
        path = os.path.join(HERE, name)
        if glb:
            js = json.dumps(self.g, sort_keys=True).encode()
            js += b" " * (-len(js) % 4)
            body = struct.pack("<II", len(js), 0x4E4F534A) + js
            body += struct.pack("<II", len(pad4(self.data)), 0x004E4942) + pad4(self.data)
            with open(path, "wb") as f:
                f.write(b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body)
        else:
            self.g["buffers"][0]["uri"] = ("data:application/octet-stream;base64," +
                                           base64.b64encode(pad4(self.data)).decode())
            with open(path, "w") as f:
                json.dump(self.g, f, indent=1, sort_keys=True)
                f.write("\n")


def cube():
    """A unit cube centred at the origin: 24 vertices (flat faces), CCW from outside, UVs per face."""
    pos, nrm, uv, idx = [], [], [], []
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    for n, u, v in faces:
        base = len(pos) // 3
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos += [0.5 * (n[k] + su * u[k] + sv * v[k]) for k in range(3)]
            nrm += list(n)
            uv += [(su + 1) / 2, 1 - (sv + 1) / 2]
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def cube_primitive(d, material=None, with_uv=True):
    pos, nrm, uv, idx = cube()
    prim = {"attributes": {"POSITION": d.floats(pos, "VEC3"), "NORMAL": d.floats(nrm, "VEC3")},
            "indices": d.indices(idx)}
    if with_uv:
        prim["attributes"]["TEXCOORD_0"] = d.floats(uv, "VEC2")
    if material is not None:
        prim["material"] = material
    return prim


def plain_cube(name, glb=False, **node):
    d = Doc()
    d.node(mesh=d.mesh("cube", [cube_primitive(d)]), **node)
    d.write(name, glb)
    return d


def mirrored():
    # Blender's "mirror" modifier applied as a negative scale: inside-out unless the winding flips.
    plain_cube("mirrored_cube.gltf", scale=[-1, 1, 1], rotation=[0, 0.3826834, 0, 0.9238795])
    plain_cube("mirrored_cube_twin.gltf", rotation=[0, 0.3826834, 0, 0.9238795])


def double_sided():
    # A quad facing away from the default camera (its front is -Z): visible only if not culled.
    d = Doc()
    pos = [-1, -1, 0, -1, 1, 0, 1, 1, 0, 1, -1, 0]
    prim = {"attributes": {"POSITION": d.floats(pos, "VEC3"), "NORMAL": d.floats([0, 0, -1] * 4, "VEC3")},
            "indices": d.indices([0, 1, 2, 0, 2, 3]), "material": 0}
    d.g["materials"] = [{"name": "leaf", "doubleSided": True,
                         "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.8, 0.2, 1]}}]
    d.node(mesh=d.mesh("leaf", [prim]))
    d.write("double_sided_quad.gltf")


def strips_fans_lines():
    # The same quad as a strip and as a fan, side by side, plus a line loop and points (refused).
    d = Doc()
    strip = [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0]           # strip order: z-shape
    fan = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]             # fan order: around the corner
    n4 = [0, 0, 1] * 4
    prims = [{"attributes": {"POSITION": d.floats(strip, "VEC3"), "NORMAL": d.floats(n4, "VEC3")}, "mode": STRIP},
             {"attributes": {"POSITION": d.floats([x + (1.5 if i % 3 == 0 else 0) for i, x in enumerate(fan)], "VEC3"),
                             "NORMAL": d.floats(n4, "VEC3")}, "mode": FAN}]
    d.node(mesh=d.mesh("strip_and_fan", prims))
    d.write("strip_fan.gltf")
    d.g["meshes"][0]["primitives"].append({"attributes": {"POSITION": d.floats(fan, "VEC3")}, "mode": 2})
    d.g["meshes"][0]["primitives"].append({"attributes": {"POSITION": d.floats(fan, "VEC3")}, "mode": POINTS})
    d.write("strip_fan_lines_points.gltf")


def interleaved():
    # One bufferView holding position, normal and texcoord per vertex (stride 32), as many
    # exporters write it, next to its tightly packed twin.
    pos, nrm, uv, idx = cube()
    d = Doc()
    rows = b"".join(struct.pack("<8f", *pos[3 * i:3 * i + 3], *nrm[3 * i:3 * i + 3], *uv[2 * i:2 * i + 2])
                    for i in range(24))
    v = d.view(rows, ARRAY_BUFFER, stride=32)
    prim = {"attributes": {
        "POSITION": d.accessor(v, FLOAT, 24, "VEC3", byteOffset=0, min=[-0.5] * 3, max=[0.5] * 3),
        "NORMAL": d.accessor(v, FLOAT, 24, "VEC3", byteOffset=12),
        "TEXCOORD_0": d.accessor(v, FLOAT, 24, "VEC2", byteOffset=24)}, "indices": d.indices(idx)}
    d.node(mesh=d.mesh("cube", [prim]), rotation=[0.2, 0.3, 0, 0.93273791])
    d.write("interleaved_cube.glb", glb=True)
    plain_cube("interleaved_cube_twin.gltf", rotation=[0.2, 0.3, 0, 0.93273791])


def skin_morph():
    # A skinned, morphing cube (as exported from an animated character): bind pose + warnings.
    d = Doc()
    prim = cube_primitive(d)
    n = 24
    prim["attributes"]["JOINTS_0"] = d.accessor(d.view(bytes([0, 0, 0, 0] * n), ARRAY_BUFFER), UBYTE, n, "VEC4")
    prim["attributes"]["WEIGHTS_0"] = d.floats([1, 0, 0, 0] * n, "VEC4")
    prim["targets"] = [{"POSITION": d.floats([0, 0.5, 0] * n, "VEC3")}]
    mesh = d.mesh("character", [prim])
    d.g["meshes"][mesh]["weights"] = [1.0]
    joint = d.node(root=False, name="root_bone")
    inverse_bind = d.floats([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], "MAT4", target=None)
    d.g["skins"] = [{"joints": [joint], "inverseBindMatrices": inverse_bind}]
    d.node(mesh=mesh, skin=0, children=[joint])
    d.write("skinned_morphed_cube.gltf")


def instancing():
    # EXT_mesh_gpu_instancing: three cubes in a row from one node.
    d = Doc()
    t = d.floats([-1.5, 0, 0, 0, 0, 0, 1.5, 0, 0], "VEC3", target=None)
    s = d.floats([0.5, 0.5, 0.5, 1, 1, 1, 0.5, 0.5, 0.5], "VEC3", target=None)
    d.node(mesh=d.mesh("cube", [cube_primitive(d)]),
           extensions={"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": t, "SCALE": s}}})
    d.g["extensionsUsed"] = ["EXT_mesh_gpu_instancing"]
    d.g["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    d.write("instanced_cubes.gltf")
    d = Doc()
    for x, sc in ((-1.5, 0.5), (0, 1), (1.5, 0.5)):
        d.node(mesh=0 if d.g["meshes"] else d.mesh("cube", [cube_primitive(d)]), translation=[x, 0, 0],
               scale=[sc] * 3)
    d.write("instanced_cubes_twin.gltf")


def material_and_attributes():
    # A PBR material as Blender exports it: every texture slot, two UV sets, vertex colours, no
    # tangents (the loader generates them). Image bytes are a tiny PNG never decoded.
    d = Doc()
    prim = cube_primitive(d, material=0)
    pos, nrm, uv, idx = cube()
    prim["attributes"]["TEXCOORD_1"] = d.floats([c * 0.5 for c in uv], "VEC2")
    colors = bytes(sum(([255, 64 * (i % 4), 0, 255] for i in range(24)), []))
    prim["attributes"]["COLOR_0"] = d.accessor(d.view(colors, ARRAY_BUFFER), UBYTE, 24, "VEC4", normalized=True)
    d.node(mesh=d.mesh("brick", [prim]))
    d.g["images"] = [{"uri": "brick.png"}]
    d.g["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 33648, "wrapT": 33071}]
    d.g["textures"] = [{"source": 0, "sampler": 0}]
    d.g["materials"] = [{
        "name": "brick",
        "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.4, 0.3, 1], "baseColorTexture": {"index": 0},
                                 "metallicFactor": 0.25, "roughnessFactor": 0.75,
                                 "metallicRoughnessTexture": {"index": 0, "texCoord": 1}},
        "normalTexture": {"index": 0, "scale": 0.5},
        "occlusionTexture": {"index": 0, "strength": 0.8, "texCoord": 1},
        "emissiveTexture": {"index": 0}, "emissiveFactor": [0.1, 0.05, 0],
        "doubleSided": False}]
    d.write("pbr_material_cube.gltf")


def lights_and_cameras():
    # KHR_lights_punctual as Blender writes it (candela for point/spot, lux for the sun) and an
    # orthographic camera.
    d = Doc()
    d.node(mesh=d.mesh("cube", [cube_primitive(d)]))
    d.g["extensionsUsed"] = ["KHR_lights_punctual"]
    d.g["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 0.9, 0.8], "intensity": 54.35, "range": 12.5,
         "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}},
        {"type": "directional", "intensity": 3.0}]}}
    d.node(translation=[0, 4, 0], rotation=[-0.7071068, 0, 0, 0.7071068],
           extensions={"KHR_lights_punctual": {"light": 0}})
    d.node(rotation=[-0.3826834, 0, 0, 0.9238795], extensions={"KHR_lights_punctual": {"light": 1}})
    d.g["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 1.5, "ymag": 1.0, "znear": 0.0, "zfar": 20}}]
    d.node(camera=0, translation=[0, 0, 5])
    d.write("spot_light_ortho_camera.gltf")


def refused():
    # Required extensions shaderlab cannot honour: refused by name before anything is decoded.
    d = Doc()
    d.node(mesh=d.mesh("cube", [cube_primitive(d, material=0)]))
    d.g["images"] = [{"uri": "brick.ktx2", "mimeType": "image/ktx2"}]
    d.g["textures"] = [{"extensions": {"KHR_texture_basisu": {"source": 0}}}]
    d.g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    d.g["extensionsUsed"] = d.g["extensionsRequired"] = ["KHR_texture_basisu"]
    d.write("basisu_textures.gltf")
    d = Doc()
    d.node(mesh=d.mesh("cube", [cube_primitive(d)]))
    d.g["extensionsUsed"] = d.g["extensionsRequired"] = ["MSFT_lod"]
    d.write("msft_lod.gltf")


def compressed():
    # The same cube compressed by the packaged encoders, when they are installed.
    d = Doc()
    d.node(mesh=d.mesh("cube", [cube_primitive(d)]), rotation=[0.2, 0.3, 0, 0.93273791])
    src = os.path.join(HERE, "_plain_for_encoders.glb")
    d.write(os.path.basename(src), glb=True)
    try:
        if shutil.which("draco_transcoder"):
            subprocess.run(["draco_transcoder", "-i", src, "-o", os.path.join(HERE, "draco_cube.glb")],
                           check=True, capture_output=True)
        if shutil.which("gltfpack"):
            # -cc: EXT_meshopt_compression with filters; quantized attributes (KHR_mesh_quantization).
            subprocess.run(["gltfpack", "-i", src, "-o", os.path.join(HERE, "meshopt_cube.glb"), "-cc", "-noq"],
                           check=True, capture_output=True)
            subprocess.run(["gltfpack", "-i", src, "-o", os.path.join(HERE, "meshopt_quantized_cube.glb"), "-cc"],
                           check=True, capture_output=True)
    finally:
        os.remove(src)
    d.write("compressed_cube_twin.glb", glb=True)


if __name__ == "__main__":
    mirrored()
    double_sided()
    strips_fans_lines()
    interleaved()
    skin_morph()
    instancing()
    material_and_attributes()
    lights_and_cameras()
    refused()
    compressed()
