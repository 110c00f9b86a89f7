#!/usr/bin/env python3
"""Writes the shipped scenes of scenes/ (run: python3 scenes/generate_scenes.py), each twice:
as glTF 2.0 (scenes/NAME.gltf) and as pbrt-v4 (scenes/pbrt/NAME.pbrt), the same scene in both.

Standard library only. Each glTF scene is one self-contained .gltf with its buffer embedded
as a base64 data URI, so a scene is a single file. The pbrt forms use what pbrt scenes use:
an Include for the shared Cornell room, bilinear patches, spheres, a binary PLY mesh, named
materials and area lights. Units are metres; emission is radiance in W/(m^2 sr) per channel
(emissiveFactor x KHR_materials_emissive_strength in glTF, "rgb L" in pbrt).

A scene lit by a sky writes it as an image beside each form, both from one function of the
direction: for pbrt an equal-area octahedral square (pbrt-v4's form, its LightSource "infinite"),
for glTF, which has no environment of its own, a latitude-longitude map that the glTF form is
rendered with (`photonfarm render scenes/NAME.gltf --environment scenes/NAME-sky.hdr`). Images
are Radiance .hdr (RGBE), which both photonfarm and pbrt-v4 read.

Scenes with lights glTF cannot express (pbrt's goniometric and projection lights) are
written as pbrt-v4 alone (PBRT_SCENES). The pbrt writer and the file formats both forms use are
in pbrt_writer.py beside this script.
"""
import base64
import json
import math
import os
import random
import struct
import sys
import zlib

sys.dont_write_bytecode = True  # no __pycache__ beside the scenes
from pbrt_writer import (PbrtWriter, cross, lat_long_to_sphere, normalize, ply_mesh,  # noqa: E402
                         ply_quads, rgbe_image, uv_sphere)


class GltfWriter:
    """Accumulates meshes, materials, nodes and lights into one glTF document."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "photonfarm generate_scenes.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [],
                    "materials": [], "accessors": [], "bufferViews": [], "buffers": []}
        self.blob = bytearray()
        self.extensions = set()
        self.side_files = {}  # written beside the .gltf: name -> bytes

    def _view(self, data, target):
        while len(self.blob) % 4:
            self.blob.append(0)
        offset = len(self.blob)
        self.blob.extend(data)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": offset,
                                        "byteLength": len(data), "target": target})
        return len(self.doc["bufferViews"]) - 1

    def _accessor(self, values, kind, component, count, target, bounds=False):
        fmt = {5126: "f", 5125: "I"}[component]
        view = self._view(struct.pack("<%d%s" % (len(values), fmt), *values), target)
        accessor = {"bufferView": view, "componentType": component, "count": count, "type": kind}
        if bounds:
            accessor["min"] = [min(values[i::3]) for i in range(3)]
            accessor["max"] = [max(values[i::3]) for i in range(3)]
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def material(self, name, color=(0.8, 0.8, 0.8), emission=None, mirror=False, glass_ior=None, alpha=0.0):
        """alpha: GGX roughness of a mirror or glass (rough metal, rough glass); glTF's
        roughnessFactor is its square root."""
        material = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(color) + [1.0], "metallicFactor": 1.0 if mirror else 0.0,
            "roughnessFactor": math.sqrt(alpha) if mirror or glass_ior else 1.0}}
        extensions = {}
        if emission is not None:
            strength = max(emission)
            material["emissiveFactor"] = [c / strength for c in emission]
            if strength != 1.0:
                extensions["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
        if glass_ior is not None:
            extensions["KHR_materials_transmission"] = {"transmissionFactor": 1.0}
            extensions["KHR_materials_ior"] = {"ior": glass_ior}
            extensions["KHR_materials_volume"] = {"thicknessFactor": 1.0}
        elif not mirror:
            # Lambertian: glTF's dielectric BRDF without its specular layer, as the pbrt forms'
            # "diffuse".
            extensions["KHR_materials_specular"] = {"specularFactor": 0.0}
        if extensions:
            material["extensions"] = extensions
            self.extensions.update(extensions)
        if emission is None:
            # pbrt's surfaces are seen from both sides; glTF's default (single-sided) would let
            # rays through an open mesh's back faces. Emitters stay single-sided: they emit from
            # their front alone, as the pbrt forms' area lights.
            material["doubleSided"] = True
        self.doc["materials"].append(material)
        return len(self.doc["materials"]) - 1

    def gltf_material(self, name, pbr, extensions):
        """A material as glTF writes it: pbrMetallicRoughness's fields and extensions as given
        (glTF-only scenes, for what pbrt has no word for)."""
        self.doc["materials"].append({"name": name, "pbrMetallicRoughness": pbr, "extensions": extensions,
                                      "doubleSided": True})
        self.extensions.update(extensions)
        return len(self.doc["materials"]) - 1

    def normal_mapped(self, name, color, image_name, png):
        """A Lambertian material whose shading normal a normal map (the PNG, linear) tilts."""
        material = self.material(name, color)
        self.doc.setdefault("images", []).append(
            {"name": image_name, "uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")})
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        self.doc["materials"][material]["normalTexture"] = {"index": len(self.doc["textures"]) - 1}
        return material

    def mesh(self, name, positions, indices, material, normals=None, uvs=None):
        flat = [c for p in positions for c in p]
        attributes = {"POSITION": self._accessor(flat, "VEC3", 5126, len(positions), 34962, True)}
        if normals:
            attributes["NORMAL"] = self._accessor([c for n in normals for c in n], "VEC3", 5126,
                                                  len(normals), 34962)
        if uvs:
            attributes["TEXCOORD_0"] = self._accessor([c for uv in uvs for c in uv], "VEC2", 5126,
                                                      len(uvs), 34962)
        index_accessor = self._accessor(indices, "SCALAR", 5125, len(indices), 34963)
        self.doc["meshes"].append({"name": name, "primitives": [
            {"attributes": attributes, "indices": index_accessor, "material": material}]})
        self.node(name, mesh=len(self.doc["meshes"]) - 1)

    def node(self, name, **fields):
        self.doc["nodes"].append(dict(name=name, **fields))
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera(self, eye, target, yfov_degrees, aspect=1.0):
        self.doc["cameras"] = [{"type": "perspective", "perspective": {
            "yfov": math.radians(yfov_degrees), "aspectRatio": aspect, "znear": 0.001}}]
        self.node("camera", camera=0, rotation=look_rotation(eye, target), translation=list(eye))

    def light(self, name, kind, color, intensity, position=None, target=None, **spot):
        lights = self.doc.setdefault("extensions", {}).setdefault(
            "KHR_lights_punctual", {"lights": []})["lights"]
        light = {"name": name, "type": kind, "color": list(color), "intensity": intensity}
        if spot:
            light["spot"] = spot
        lights.append(light)
        self.extensions.add("KHR_lights_punctual")
        fields = {"extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}}
        if position is not None:
            fields["translation"] = list(position)
        if target is not None:
            fields["rotation"] = look_rotation(position or (0, 0, 0), target)
        self.node(name, **fields)

    def sphere(self, name, center, radius, material, as_mesh=False):
        """A UV sphere about the y axis, with vertex normals."""
        positions, indices, normals = uv_sphere(center, radius)
        self.mesh(name, positions, indices, material, normals)

    def quads(self, name, quad_list, material, ply=None, uvs=None):
        """Planar quads (4 corners each, counter-clockwise seen from the lit side); uvs: each
        corner's texture coordinates (u, v), v up the image as pbrt's (glTF's is 1 - v)."""
        positions, indices = [], []
        for quad in quad_list:
            base = len(positions)
            positions.extend([[float(c) for c in p] for p in quad])
            indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])
        self.mesh(name, positions, indices, material,
                  uvs=[[u, 1 - v] for u, v in uvs] if uvs else None)

    def image_light(self, name, quad, color, scale, image_name, png):
        """A quad emitting scale x the PNG image (sRGB), its top left at the quad's corner 3
        and its bottom left at corner 0: emissiveTexture x emissiveFactor x strength."""
        self.doc.setdefault("images", []).append(
            {"name": image_name, "uri": "data:image/png;base64," + base64.b64encode(png).decode("ascii")})
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        self.doc["materials"].append({
            "name": name, "pbrMetallicRoughness": {"baseColorFactor": list(color) + [1.0], "metallicFactor": 0.0},
            "emissiveFactor": [1.0, 1.0, 1.0], "emissiveTexture": {"index": len(self.doc["textures"]) - 1},
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": scale},
                           "KHR_materials_specular": {"specularFactor": 0.0}}})
        self.extensions.update(["KHR_materials_emissive_strength", "KHR_materials_specular"])
        self.mesh(name, [[float(c) for c in p] for p in quad], [0, 1, 2, 0, 2, 3],
                  len(self.doc["materials"]) - 1, uvs=[[0, 1], [1, 1], [1, 0], [0, 0]])

    def begin_shared(self, name):
        """Starts a part other scenes share (the pbrt form puts it in its own file)."""

    def end_shared(self):
        pass

    def environment(self, scene_name, sky):
        """glTF has no environment: a latitude-longitude map beside the file, named in the
        asset's extras for whoever reads it (photonfarm takes it by --environment)."""
        name = scene_name + "-sky.hdr"
        self.side_files[name] = rgbe_image(256, 128, lambda u, v: sky(lat_long_to_sphere(u, v)))
        self.doc["asset"]["extras"] = {"environment": name, "render with": "--environment " + name}

    def write(self, path):
        self.doc["buffers"] = [{"byteLength": len(self.blob), "uri":
                                "data:application/octet-stream;base64," +
                                base64.b64encode(bytes(self.blob)).decode("ascii")}]
        if self.extensions:
            self.doc["extensionsUsed"] = sorted(self.extensions)
        with open(path, "w") as out:
            json.dump(self.doc, out, indent=1)
            out.write("\n")
        for name, data in self.side_files.items():
            with open(os.path.join(os.path.dirname(path), name), "wb") as out:
                out.write(data)


def look_rotation(eye, target):
    """Quaternion [x, y, z, w] turning glTF's camera frame (looks down -Z, +Y up) toward target."""
    forward = normalize([t - e for t, e in zip(target, eye)])
    up_hint = [0, 1, 0] if abs(forward[1]) < 0.999 else [0, 0, 1]
    right = normalize(cross(forward, up_hint))
    up = cross(right, forward)
    back = [-c for c in forward]
    m = [[right[0], up[0], back[0]], [right[1], up[1], back[1]], [right[2], up[2], back[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 0.5 / math.sqrt(trace + 1.0)
        q = [(m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, 0.25 / s]
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2])
        q = [0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s]
    elif m[1][1] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2])
        q = [(m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1])
        q = [(m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s]
    return normalize(q)


def mm(quad_list):
    """Millimetres to metres."""
    return [[[c * 0.001 for c in p] for p in quad] for quad in quad_list]


# The Cornell box as measured (Cornell University Program of Computer Graphics), in mm.
CORNELL_WALLS = {
    "floor": [[552.8, 0, 0], [0, 0, 0], [0, 0, 559.2], [549.6, 0, 559.2]],
    "ceiling": [[556, 548.8, 0], [556, 548.8, 559.2], [0, 548.8, 559.2], [0, 548.8, 0]],
    "back": [[549.6, 0, 559.2], [0, 0, 559.2], [0, 548.8, 559.2], [556, 548.8, 559.2]],
    "right_green": [[0, 0, 559.2], [0, 0, 0], [0, 548.8, 0], [0, 548.8, 559.2]],
    "left_red": [[552.8, 0, 0], [549.6, 0, 559.2], [556, 548.8, 559.2], [556, 548.8, 0]],
}
CORNELL_LIGHT = [[343, 548.7, 227], [343, 548.7, 332], [213, 548.7, 332], [213, 548.7, 227]]
SHORT_BLOCK = [[[130, 165, 65], [82, 165, 225], [240, 165, 272], [290, 165, 114]],
               [[290, 0, 114], [290, 165, 114], [240, 165, 272], [240, 0, 272]],
               [[130, 0, 65], [130, 165, 65], [290, 165, 114], [290, 0, 114]],
               [[82, 0, 225], [82, 165, 225], [130, 165, 65], [130, 0, 65]],
               [[240, 0, 272], [240, 165, 272], [82, 165, 225], [82, 0, 225]]]
TALL_BLOCK = [[[423, 330, 247], [265, 330, 296], [314, 330, 456], [472, 330, 406]],
              [[423, 0, 247], [423, 330, 247], [472, 330, 406], [472, 0, 406]],
              [[472, 0, 406], [472, 330, 406], [314, 330, 456], [314, 0, 456]],
              [[314, 0, 456], [314, 330, 456], [265, 330, 296], [265, 0, 296]],
              [[265, 0, 296], [265, 330, 296], [423, 330, 247], [423, 0, 247]]]
WHITE, RED, GREEN = (0.725, 0.71, 0.68), (0.63, 0.065, 0.05), (0.14, 0.45, 0.091)
LIGHT_RADIANCE = (17.0, 12.0, 4.0)


def cornell_room(writer, light=True):
    writer.begin_shared("cornell-room" if light else "cornell-walls")
    white = writer.material("white", WHITE)
    for name in ("floor", "ceiling", "back"):
        writer.quads(name, mm([CORNELL_WALLS[name]]), white)
    writer.quads("left_red", mm([CORNELL_WALLS["left_red"]]), writer.material("red", RED))
    writer.quads("right_green", mm([CORNELL_WALLS["right_green"]]), writer.material("green", GREEN))
    if light:
        writer.quads("light", mm([CORNELL_LIGHT]),
                     writer.material("light", (0.78, 0.78, 0.78), LIGHT_RADIANCE))
    writer.end_shared()
    # The measured camera: 35 mm focal length on a 25 mm film, looking down +z.
    writer.camera([0.278, 0.273, -0.8], [0.278, 0.273, 0.0], math.degrees(2 * math.atan(12.5 / 35)))
    return white


def cornell_box(writer):
    white = cornell_room(writer)
    writer.quads("short_block", mm(SHORT_BLOCK), white)
    writer.quads("tall_block", mm(TALL_BLOCK), white, ply="tall-block")


def stained_glass(width=64, tiles=4, lead=2):
    """An sRGB PNG of coloured tiles between dark lead lines, as a stained-glass window."""
    colors = [(240, 140, 120), (245, 215, 140), (140, 165, 240), (160, 225, 200), (225, 230, 245),
              (195, 155, 240)]
    tile = width // tiles
    rows = []
    for y in range(width):
        row = bytearray([0])  # filter: none
        for x in range(width):
            tx, ty = x // tile, y // tile
            edge = min(x % tile, y % tile, tile - 1 - x % tile, tile - 1 - y % tile) < lead // 2 + lead % 2
            row += bytes((25, 20, 15)) if edge else bytes(colors[(tx * 5 + ty * 3 + tx * ty) % len(colors)])
        rows.append(bytes(row))

    return png_rgb(width, width, rows)


def png_rgb(width, height, rows):
    """An 8-bit RGB PNG of `rows` (each a filter byte 0, then width RGB triples)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) + chunk(b"IEND", b""))


def bevelled_tiles(width=64, tiles=2, bevel=6, slope=1.0):
    """A tangent-space normal map (linear RGB, x right and y up the image, as glTF and pbrt read
    it) of square tiles whose edges are bevelled down into the grout: flat on each tile's top,
    tilted away from its centre within `bevel` texels of its edge by `slope`."""
    tile = width // tiles
    rows = []
    for row in range(width):
        line = bytearray([0])
        for column in range(width):
            x, y = column % tile + 0.5, tile - row % tile - 0.5  # y up the image
            to_x, to_y = min(x, tile - x), min(y, tile - y)  # to the nearest edges
            dx = dy = 0.0
            if min(to_x, to_y) < bevel:  # on a bevel: tilted toward its edge
                if to_x < to_y:
                    dx = -slope if x < tile / 2 else slope
                else:
                    dy = -slope if y < tile / 2 else slope
            n = normalize([dx, dy, 1.0])
            line += bytes(round((c + 1) / 2 * 255) for c in n)
        rows.append(bytes(line))
    return png_rgb(width, width, rows)


def cornell_stained(writer):
    """The Cornell box lit by a stained-glass panel in place of its light: an area light whose
    emission is an image (pbrt's "filename", glTF's emissiveTexture), 4 x 4 coloured tiles
    between lead lines, photons and light samples leaving each texel by its power."""
    white = cornell_room(writer, light=False)
    writer.quads("short_block", mm(SHORT_BLOCK), white)
    writer.quads("tall_block", mm(TALL_BLOCK), white)
    panel = [[400, 548.7, 180], [400, 548.7, 380], [156, 548.7, 380], [156, 548.7, 180]]
    writer.image_light("stained_glass", mm([panel])[0], (0.78, 0.78, 0.78), 16.0,
                       "cornell-stained-glass.png", stained_glass())


def cornell_bumpy(writer):
    """The Cornell box with a tiled floor and back wall: a normal map bevels each tile's edges,
    so the light catches the bevels facing it and photons leave them by the tilted normals."""
    tiles = writer.normal_mapped("tiles", WHITE, "cornell-bumpy-tiles.png", bevelled_tiles())
    white = writer.material("white", WHITE)
    repeat = [[0, 0], [3, 0], [3, 3], [0, 3]]  # 3 x 3 copies of the map's 2 x 2 tiles
    for name in ("floor", "back"):
        writer.quads(name, mm([CORNELL_WALLS[name]]), tiles, uvs=repeat)
    writer.quads("ceiling", mm([CORNELL_WALLS["ceiling"]]), white)
    writer.quads("left_red", mm([CORNELL_WALLS["left_red"]]), writer.material("red", RED))
    writer.quads("right_green", mm([CORNELL_WALLS["right_green"]]), writer.material("green", GREEN))
    writer.quads("light", mm([CORNELL_LIGHT]),
                 writer.material("light", (0.78, 0.78, 0.78), LIGHT_RADIANCE))
    writer.quads("short_block", mm(SHORT_BLOCK), white)
    writer.quads("tall_block", mm(TALL_BLOCK), white)
    writer.camera([0.278, 0.273, -0.8], [0.278, 0.273, 0.0], math.degrees(2 * math.atan(12.5 / 35)))


def lamp_shade(direction):
    """A hanging lamp's intensity, relative, over its sphere of directions (y up): most of it
    downward, through six slots of its shade, and a dim glow up toward the ceiling."""
    x, y, z = direction
    phi = math.atan2(z, x)
    slots = 0.25 + 0.75 * max(0.0, math.cos(3 * phi)) ** 4
    return [0.15 + 2.0 * max(0.0, -y) ** 2 * slots] * 3


def cornell_lamps(writer):
    """The Cornell box without its ceiling light, lit by a slide projector (pbrt's projection
    light) casting the stained-glass picture across the back wall and the blocks, and by a
    hanging goniometric lamp whose shade throws six beams on the floor."""
    white = cornell_room(writer, light=False)
    writer.quads("short_block", mm(SHORT_BLOCK), white)
    writer.quads("tall_block", mm(TALL_BLOCK), white)
    writer.projection_light("projector", [0.2, 0.36, -0.25], [0.3, 0.26, 0.5592], 28.0, 2.5,
                            "cornell-stained-glass.png", stained_glass())
    writer.goniometric_light("lamp", [0.278, 0.42, 0.28], (1.0, 0.85, 0.62), 0.35,
                             "cornell-lamps-shade.hdr", lamp_shade)


def cornell_materials(writer):
    """The Cornell box in pbrt-v4's materials beyond the diffuse and the glass: a coated short
    block (coateddiffuse), a tall block that is a mix of red paint and rough gold at each point
    (mix, conductor), and a sheet of paper (diffusetransmission) hung under the light, which
    lights the room below it through the sheet."""
    cornell_room(writer)
    coated = writer.named_material("coated_blue", "coateddiffuse",
                                   '"rgb reflectance" [ 0.3 0.5 0.7 ] "float roughness" 0.3')
    writer.named_material("red_paint", "diffuse", '"rgb reflectance" [ 0.7 0.15 0.1 ]')
    writer.named_material("gold", "conductor", '"spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" '
                                               '"float roughness" 0.5')
    mixed = writer.named_material("paint_and_gold", "mix",
                                  '"string materials" [ "red_paint" "gold" ] "float amount" 0.4')
    paper = writer.named_material("paper", "diffusetransmission",
                                  '"rgb reflectance" [ 0.5 0.45 0.4 ] "rgb transmittance" [ 0.4 0.4 0.35 ]')
    writer.quads("short_block", mm(SHORT_BLOCK), coated)
    writer.quads("tall_block", mm(TALL_BLOCK), mixed)
    writer.quads("paper", mm([[[180, 470, 190], [280, 470, 190], [280, 470, 370], [180, 470, 370]]]), paper)


def cornell_glass(writer):
    cornell_room(writer)
    writer.sphere("mirror_sphere", [0.385, 0.1, 0.37], 0.1,
                  writer.material("mirror", (0.95, 0.95, 0.95), mirror=True))
    writer.sphere("glass_sphere", [0.175, 0.1, 0.18], 0.1,
                  writer.material("glass", (1.0, 1.0, 1.0), glass_ior=1.5))


def cornell_glossy(writer):
    """The Cornell room with a rough metal sphere and a rough glass sphere: glossy reflections
    and a blurred caustic, which stochastic progressive photon mapping resolves and plain
    progressive photon mapping, whose hit points never move, leaves noisy."""
    cornell_room(writer)
    writer.sphere("rough_metal_sphere", [0.385, 0.1, 0.37], 0.1,
                  writer.material("rough_metal", (0.9, 0.75, 0.45), mirror=True, alpha=0.1))
    writer.sphere("rough_glass_sphere", [0.175, 0.1, 0.18], 0.1,
                  writer.material("rough_glass", (1.0, 1.0, 1.0), glass_ior=1.5, alpha=0.05))


def cornell_velvet(writer):
    """The Cornell box with glTF's layered materials on its blocks (KHR_materials_sheen, which
    pbrt has no word for): the short block velvet, a sheen over rough purple metal as in the
    Khronos SheenChair's fabric; the tall block plastic, glTF's dielectric with a rough specular
    layer, under a faint white sheen."""
    cornell_room(writer)
    velvet = writer.gltf_material(
        "velvet", {"baseColorFactor": [0.35, 0.12, 0.4, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.6},
        {"KHR_materials_sheen": {"sheenColorFactor": [1.0, 0.2, 0.75], "sheenRoughnessFactor": 0.5}})
    plastic = writer.gltf_material(
        "plastic", {"baseColorFactor": [0.7, 0.7, 0.65, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.45},
        {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.5, 0.5], "sheenRoughnessFactor": 0.3}})
    writer.quads("short_block", mm(SHORT_BLOCK), velvet)
    writer.quads("tall_block", mm(TALL_BLOCK), plastic)


def caustic_glass(writer):
    writer.quads("plane", [[[-2, 0, -2], [-2, 0, 2], [2, 0, 2], [2, 0, -2]]],
                 writer.material("plane", (0.75, 0.75, 0.75)))
    writer.sphere("glass_sphere", [0, 0.5, 0], 0.5,
                  writer.material("glass", (1.0, 1.0, 1.0), glass_ior=1.5), as_mesh=True)
    s = 0.05
    writer.quads("light", [[[1.5 - s, 2.5, -s], [1.5 + s, 2.5, -s], [1.5 + s, 2.5, s], [1.5 - s, 2.5, s]]],
                 writer.material("light", (0.0, 0.0, 0.0), (4000.0, 4000.0, 4000.0)))
    writer.camera([-0.6, 2.6, 3.4], [0.1, 0.2, 0.0], 40.0)


def furnace(writer, albedo=0.5, emission=1.0):
    """A closed cube whose every wall has albedo rho and emits Le: L = Le / (1 - rho) everywhere."""
    material = writer.material("wall", (albedo,) * 3, (emission,) * 3)
    h = 1.0
    faces = []
    for axis in range(3):
        for side in (-h, h):
            # Four corners of the face at coordinate `side` on `axis`, wound to face the centre.
            u, v = (axis + 1) % 3, (axis + 2) % 3
            face = []
            for a, b in ((-h, -h), (h, -h), (h, h), (-h, h)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = side, a, b
                face.append(p)
            faces.append(face[::-1] if side > 0 else face)
    writer.quads("room", faces, material)
    writer.camera([0.0, 0.0, 0.5], [0.3, -0.2, -1.0], 70.0)


def sky(direction):
    """A clear sky with a bright glow about the sun, over dark ground, W/(m^2 sr)."""
    x, y, z = direction
    sun = normalize([0.45, 0.55, -0.7])
    glow = 40.0 * max(0.0, x * sun[0] + y * sun[1] + z * sun[2]) ** 300
    ground, horizon, zenith = (0.08, 0.07, 0.06), (0.9, 0.85, 0.8), (0.25, 0.45, 0.95)
    t = math.sqrt(max(0.0, y))
    air = [h + (zz - h) * t for h, zz in zip(horizon, zenith)]
    # Ground to sky over 6 degrees, so that the map's texels do not show as steps at the horizon.
    blend = min(1.0, max(0.0, (y + 0.05) / 0.1))
    return [g + (a - g) * blend + glow for g, a in zip(ground, air)]


def sky_courtyard(writer):
    """An open corner of two walls on the ground, a block and a glass sphere under a sky:
    lit only by the environment (photons from it, light sampled from its map)."""
    writer.quads("ground", [[[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]],
                 writer.material("ground", (0.45, 0.45, 0.42)))
    warm = writer.material("warm_wall", (0.75, 0.55, 0.4))
    writer.quads("walls", [[[-1.5, 0, -1.5], [1.5, 0, -1.5], [1.5, 1.5, -1.5], [-1.5, 1.5, -1.5]],
                           [[-1.5, 0, 1.0], [-1.5, 0, -1.5], [-1.5, 1.5, -1.5], [-1.5, 1.5, 1.0]]], warm)
    white = writer.material("white", (0.8, 0.8, 0.8))
    b = [(-0.9, -0.9), (-0.3, -1.1), (-0.1, -0.5), (-0.7, -0.3)]  # a turned block, 0.6 tall
    faces = [[[x0, 0.6, z0] for x0, z0 in reversed(b)]]
    for i in range(4):
        (x0, z0), (x1, z1) = b[i], b[(i + 1) % 4]
        faces.append([[x0, 0, z0], [x1, 0, z1], [x1, 0.6, z1], [x0, 0.6, z0]])
    writer.quads("block", faces, white)
    writer.sphere("glass_sphere", [0.5, 0.35, -0.2], 0.35, writer.material("glass", glass_ior=1.5))
    writer.environment("sky-courtyard", sky)
    writer.camera([2.2, 1.6, 2.8], [-0.3, 0.4, -0.6], 45.0, aspect=1.5)


def furnace_glass(writer):
    """The furnace with a clear glass sphere in view: lossless scattering leaves the uniform
    radiance field uniform, so every pixel, through the glass or not, is still Le / (1 - rho)."""
    furnace(writer)
    writer.sphere("glass_sphere", [0.25, -0.3, -0.45], 0.35,
                  writer.material("glass", (1.0, 1.0, 1.0), glass_ior=1.5))


def light_gap(writer):
    """A room lit only through a slit: a small lamp outside, facing a narrow opening in one wall,
    over ground that runs on outside. The camera looks at the far wall and the ceiling, where no
    direct light falls: everything it sees is light that came in through the slit and bounced,
    which only the few photons that get in (about one in twenty) carry. The scene adaptive photon
    tracing is for (docs/integrators.md)."""
    white = writer.material("white", (0.7, 0.7, 0.7))
    w, h, d = 4.0, 2.5, 4.0  # the room: x in [0, w], y in [0, h], z in [0, d]
    writer.quads("floor", [[[0, 0, 0], [0, 0, d], [w, 0, d], [w, 0, 0]]], white)
    writer.quads("ceiling", [[[0, h, 0], [w, h, 0], [w, h, d], [0, h, d]]], white)
    writer.quads("walls", [[[0, 0, 0], [w, 0, 0], [w, h, 0], [0, h, 0]],
                           [[0, 0, d], [0, h, d], [w, h, d], [w, 0, d]],
                           [[0, 0, 0], [0, h, 0], [0, h, d], [0, 0, d]]], white)
    # The wall at x = w, with a slit 0.12 wide and 1.2 high, 0.5 above the floor, at z = 2.
    s0, s1, y0, y1 = 1.94, 2.06, 0.5, 1.7
    writer.quads("slit_wall", [[[w, 0, 0], [w, 0, s0], [w, h, s0], [w, h, 0]],
                               [[w, 0, s1], [w, 0, d], [w, h, d], [w, h, s1]],
                               [[w, 0, s0], [w, 0, s1], [w, y0, s1], [w, y0, s0]],
                               [[w, y1, s0], [w, y1, s1], [w, h, s1], [w, h, s0]]], white)
    writer.quads("ground", [[[-6, -0.01, -6], [-6, -0.01, 10], [10, -0.01, 10], [10, -0.01, -6]]],
                 writer.material("ground", (0.5, 0.5, 0.5)))
    # The lamp: 0.2 m square, 1 m outside the slit and above its top, facing it (-x): its light
    # comes in downward, onto the floor, out of the camera's view.
    x, c, r = w + 1.0, 2.0, 0.1
    writer.quads("lamp", [[[x, 2.0 - r, c - r], [x, 2.0 - r, c + r], [x, 2.0 + r, c + r], [x, 2.0 + r, c - r]]],
                 writer.material("lamp", (0.0, 0.0, 0.0), (2400.0, 2240.0, 1920.0)))
    writer.camera([2.0, 1.2, 0.3], [2.0, 2.2, 4.0], 60.0)


def caustic_room(writer):
    """A small glass sphere on the floor of a large room (12 x 4 x 12 m) under a ceiling lamp,
    seen close up with its caustic: the camera sees about a square metre of floor, and the
    whole room mirrored in the sphere. The caustic's photons are few of those emitted, but most
    photons reach something the camera sees (through the mirror): adaptive photon tracing's
    counter-case (docs/integrators.md)."""
    white = writer.material("white", (0.6, 0.6, 0.6))
    a, h = 6.0, 4.0
    writer.quads("floor", [[[-a, 0, -a], [-a, 0, a], [a, 0, a], [a, 0, -a]]], white)
    writer.quads("ceiling", [[[-a, h, -a], [a, h, -a], [a, h, a], [-a, h, a]]], white)
    writer.quads("walls", [[[-a, 0, -a], [a, 0, -a], [a, h, -a], [-a, h, -a]],
                           [[-a, 0, a], [-a, h, a], [a, h, a], [a, 0, a]],
                           [[-a, 0, -a], [-a, h, -a], [-a, h, a], [-a, 0, a]],
                           [[a, 0, -a], [a, 0, a], [a, h, a], [a, h, -a]]], white)
    r = 0.25
    writer.quads("lamp", [[[-r, h - 0.01, -r], [r, h - 0.01, -r], [r, h - 0.01, r], [-r, h - 0.01, r]]],
                 writer.material("lamp", (0.0, 0.0, 0.0), (80.0, 80.0, 80.0)))
    writer.sphere("small_glass_sphere", [1.2, 0.15, 0.0], 0.15,
                  writer.material("glass", (1.0, 1.0, 1.0), glass_ior=1.5), as_mesh=True)
    writer.camera([0.7, 0.8, 0.9], [1.3, 0.0, 0.0], 50.0)


def cornell_curves(writer):
    """The Cornell box in pbrt-v4's curves: three tufts of grass (tapered cylinder curves, one
    object instanced three times, in pbrt-v4's hair material, which photonfarm shades as the
    nearest diffuse surface), a curtain of flat B-spline strands hanging before the back wall, and
    three broad ribbon leaves (degree 2 Bezier curves, each turning between the normals at its
    ends). Seeded: the same file every time."""
    cornell_room(writer)
    rng = random.Random(57)
    grass = writer.named_material("grass", "hair", '"rgb reflectance" [ 0.3 0.55 0.15 ]')
    writer.begin_object("tuft")
    blades = []
    for _ in range(40):
        angle, lean = rng.uniform(0, 2 * math.pi), rng.uniform(0.02, 0.07)
        height = rng.uniform(0.09, 0.16)
        x0, z0 = rng.gauss(0, 0.012), rng.gauss(0, 0.012)
        dx, dz = math.cos(angle) * lean, math.sin(angle) * lean
        blades.append([[x0, 0, z0], [x0 + 0.1 * dx, height / 3, z0 + 0.1 * dz],
                       [x0 + 0.5 * dx, 2 * height / 3, z0 + 0.5 * dz], [x0 + dx, height, z0 + dz]])
    writer.curves("blades", blades, grass,
                  '"string type" "cylinder" "float width0" 0.006 "float width1" 0.001')
    writer.end_object()
    for x, z, turn, size in ((0.15, 0.2, 0, 1.0), (0.38, 0.12, 70, 1.2), (0.3, 0.35, 150, 0.9)):
        writer.instance("tuft", [x, 0, z], turn, size)
    strands = []
    for i in range(14):
        x = 0.12 + 0.32 * i / 13
        sway = [rng.uniform(-0.03, 0.03) for _ in range(3)]
        strands.append([[x, 0.52, 0.5], [x + sway[0], 0.44, 0.49], [x + sway[1], 0.36, 0.5],
                        [x + sway[2], 0.28, 0.48], [x, 0.22, 0.5]])
    writer.curves("strands", strands, writer.material("straw", (0.8, 0.7, 0.35)),
                  '"string basis" "bspline" "float width" 0.004')
    leaf = writer.material("leaf", (0.2, 0.5, 0.25))
    for i, (x, z) in enumerate(((0.42, 0.3), (0.2, 0.42), (0.48, 0.22))):
        tip = [x - 0.08 + 0.05 * i, 0.22, z - 0.05]
        writer.ribbon("leaf_%d" % i, [[x, 0, z], [x - 0.02, 0.14, z + 0.02], tip],
                      [[1, 0, 0], [0.6, 0.3, -0.74]], leaf,
                      '"integer degree" 2 "float width0" 0.05 "float width1" 0.012')


SCENES = {"cornell-box": cornell_box, "cornell-glass": cornell_glass, "cornell-glossy": cornell_glossy,
          "caustic-glass": caustic_glass, "furnace": furnace, "furnace-glass": furnace_glass,
          "sky-courtyard": sky_courtyard, "cornell-stained": cornell_stained,
          "cornell-bumpy": cornell_bumpy, "light-gap": light_gap, "caustic-room": caustic_room}
PBRT_SCENES = {"cornell-lamps": cornell_lamps, "cornell-materials": cornell_materials,
               "cornell-curves": cornell_curves}
GLTF_SCENES = {"cornell-velvet": cornell_velvet}

if __name__ == "__main__":
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    for scene_name, build in SCENES.items():
        for writer, path in ((GltfWriter(), os.path.join(out_dir, scene_name + ".gltf")),
                             (PbrtWriter(scene_name), os.path.join(out_dir, "pbrt", scene_name + ".pbrt"))):
            build(writer)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            writer.write(path)
            print("wrote", path)
    for scene_name, build in GLTF_SCENES.items():
        writer, path = GltfWriter(), os.path.join(out_dir, scene_name + ".gltf")
        build(writer)
        writer.write(path)
        print("wrote", path)
    for scene_name, build in PBRT_SCENES.items():
        writer, path = PbrtWriter(scene_name, gltf_twin=False), os.path.join(out_dir, "pbrt", scene_name + ".pbrt")
        build(writer)
        writer.write(path)
        print("wrote", path)
