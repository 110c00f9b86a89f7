"""The pbrt-v4 form of scenes/generate_scenes.py's scenes (PbrtWriter), and the file formats and
maps both forms share: Radiance .hdr, binary PLY, the equal-area and latitude-longitude maps of
the sphere. Standard library only."""
import math
import os
import struct


def normalize(v):
    length = math.sqrt(sum(c * c for c in v))
    return [c / length for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def uv_sphere(center, radius, rings=48, segments=96):
    """Positions, indices and normals of a UV sphere about the y axis."""
    positions, normals, indices = [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = [math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)]
            normals.append(n)
            positions.append([c + radius * d for c, d in zip(center, n)])
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            if i != 0:
                indices.extend([a, a + 1, b])
            if i != rings - 1:
                indices.extend([a + 1, b + 1, b])
    return positions, indices, normals


class PbrtWriter:
    """The same scene calls as GltfWriter, written as a pbrt-v4 scene."""

    def __init__(self, name, gltf_twin=True):
        self.name = name
        self.gltf_twin = gltf_twin  # whether the glTF form of the same scene is written too
        self.header = []
        self.world = []
        self.shared = None          # (name, lines) while a shared part is being written
        self.files = {}             # extra files: relative path -> bytes
        self.materials = {}

    def _out(self):
        return self.shared[1] if self.shared else self.world

    def material(self, name, color=(0.8, 0.8, 0.8), emission=None, mirror=False, glass_ior=None, alpha=0.0):
        rough = ' "float roughness" %s "bool remaproughness" false' % num(alpha) if alpha > 0 else ""
        if mirror:
            line = 'MakeNamedMaterial "%s" "string type" "conductor" "rgb reflectance" %s%s' % (name, rgb(color), rough)
        elif glass_ior is not None:
            line = 'MakeNamedMaterial "%s" "string type" "dielectric" "float eta" %s%s' % (name, num(glass_ior), rough)
        else:
            line = 'MakeNamedMaterial "%s" "string type" "diffuse" "rgb reflectance" %s' % (name, rgb(color))
        self._out().append(line)
        self.materials[name] = emission
        return name

    def named_material(self, name, material_type, parameters):
        """Any pbrt-v4 material, its parameters as pbrt-v4 writes them (pbrt-only scenes)."""
        self._out().append('MakeNamedMaterial "%s" "string type" "%s" %s' % (name, material_type, parameters))
        self.materials[name] = None
        return name

    def normal_mapped(self, name, color, image_name, png):
        """A diffuse material with pbrt-v4's "normalmap" (the PNG, read linear)."""
        path = "textures/%s" % image_name
        self.files[path] = png
        self._out().append('MakeNamedMaterial "%s" "string type" "diffuse" "rgb reflectance" %s '
                           '"string normalmap" "%s"' % (name, rgb(color), path))
        self.materials[name] = None
        return name

    def _begin(self, name, material):
        out = self._out()
        out.append("")
        out.append("# " + name)
        out.append("AttributeBegin")
        if self.materials[material] is not None:
            out.append('    AreaLightSource "diffuse" "rgb L" %s' % rgb(self.materials[material]))
        out.append('    NamedMaterial "%s"' % material)
        return out

    def quads(self, name, quad_list, material, ply=None, uvs=None):
        """uvs: each corner's (u, v) of a single quad, v up the image (pbrt's own)."""
        out = self._begin(name, material)
        points = [c for quad in quad_list for p in quad for c in p]
        if ply:
            path = "meshes/%s.ply" % ply
            self.files[path] = ply_quads(quad_list)
            out.append('    Shape "plymesh" "string filename" "%s"' % path)
        else:
            # Bilinear patches: corners p00 p10 p01 p11, i.e. the quad's 0, 1, 3, 2.
            indices = []
            for q in range(len(quad_list)):
                indices.extend([4 * q, 4 * q + 1, 4 * q + 3, 4 * q + 2])
            line = '    Shape "bilinearmesh" "point3 P" %s "integer indices" %s' % (
                numbers(points), numbers(indices))
            if uvs:
                line += ' "point2 uv" %s' % numbers([c for uv in uvs for c in uv])
            out.append(line)
        out.append("AttributeEnd")

    def sphere(self, name, center, radius, material, as_mesh=False):
        """pbrt's own sphere, or with as_mesh the glTF form's exact triangles (for a caustic,
        whose shape depends on the facets)."""
        if as_mesh:
            path = "meshes/%s.ply" % name.replace("_", "-")
            self.files[path] = ply_mesh(*uv_sphere(center, radius))
            out = self._begin(name, material)
            out.append('    Shape "plymesh" "string filename" "%s"' % path)
            out.append("AttributeEnd")
            return
        out = self._begin(name, material)
        out.append("    Translate %s %s %s" % tuple(num(c) for c in center))
        out.append("    Rotate -90 1 0 0  # pbrt's spheres have their poles on z; these on y")
        out.append('    Shape "sphere" "float radius" %s' % num(radius))
        out.append("AttributeEnd")

    def mesh(self, name, positions, indices, material, normals=None):
        out = self._begin(name, material)
        line = '    Shape "trianglemesh" "point3 P" %s "integer indices" %s' % (
            numbers([c for p in positions for c in p]), numbers(indices))
        if normals:
            line += ' "normal N" %s' % numbers([c for n in normals for c in n])
        out.append(line)
        out.append("AttributeEnd")

    def curves(self, name, curve_list, material, parameters=""):
        """pbrt-v4 curve shapes (pbrt-only scenes): each a list of control points, with the same
        further parameters (type, basis, widths) written as pbrt-v4 writes them."""
        out = self._begin(name, material)
        for points in curve_list:
            out.append('    Shape "curve" "point3 P" %s %s' % (numbers([c for p in points for c in p]),
                                                          parameters))
        out.append("AttributeEnd")

    def ribbon(self, name, points, normals, material, parameters=""):
        """A pbrt-v4 ribbon curve: a normal at each segment's ends."""
        out = self._begin(name, material)
        out.append('    Shape "curve" "string type" "ribbon" "point3 P" %s "normal N" %s %s' % (
            numbers([c for p in points for c in p]), numbers([c for n in normals for c in n]), parameters))
        out.append("AttributeEnd")

    def begin_object(self, name):
        """What follows until end_object is pbrt's object `name` (ObjectBegin), drawn by instance()."""
        self._out().extend(["", 'ObjectBegin "%s"' % name])

    def end_object(self):
        self._out().append("ObjectEnd")

    def instance(self, name, translate, rotate_y_degrees=0.0, scale=1.0):
        self._out().extend(["AttributeBegin",
                            "    Translate %s %s %s" % tuple(num(c) for c in translate),
                            "    Rotate %s 0 1 0" % num(rotate_y_degrees),
                            "    Scale %s %s %s" % ((num(scale),) * 3),
                            '    ObjectInstance "%s"' % name, "AttributeEnd"])

    def camera(self, eye, target, yfov_degrees, aspect=1.0):
        up = [0, 1, 0] if abs(normalize([t - e for t, e in zip(target, eye)])[1]) < 0.999 else [0, 0, 1]
        self.header = [
            "# %s, written by scenes/generate_scenes.py%s." % (
                self.name, "; the same scene as ../%s.gltf" % self.name if self.gltf_twin else ""),
            "# pbrt's camera space is left-handed: mirroring x gives glTF's right-handed view.",
            "Scale -1 1 1",
            "LookAt %s  %s  %s" % (" ".join(num(c) for c in eye), " ".join(num(c) for c in target),
                                   " ".join(num(c) for c in up)),
            'Camera "perspective" "float fov" %s' % num(yfov_degrees if aspect >= 1 else
                                                      math.degrees(2 * math.atan(math.tan(math.radians(yfov_degrees) / 2) * aspect))),
            'Film "rgb" "integer xresolution" 512 "integer yresolution" %d' % round(512 / aspect),
        ]
        if self.gltf_twin:  # glTF knows no pixel filter: both forms average each pixel's samples
            self.header.append('PixelFilter "box"')

    def light(self, *args, **kwargs):
        raise NotImplementedError("punctual lights are written to glTF scenes only")

    def image_light(self, name, quad, color, scale, image_name, png):
        """An area light with pbrt-v4's "filename": the image over the bilinear patch's (u, v),
        v up, so that p00 (corner 0) is its bottom left."""
        path = "textures/%s" % image_name
        self.files[path] = png
        out = self._out()
        out += ["", "# " + name, "AttributeBegin",
                '    AreaLightSource "diffuse" "string filename" "%s" "float scale" %s' % (path, num(scale)),
                '    Material "diffuse" "rgb reflectance" %s' % rgb(color),
                '    Shape "bilinearmesh" "point3 P" %s' % numbers([c for i in (0, 1, 3, 2) for c in quad[i]]),
                "AttributeEnd"]

    def projection_light(self, name, eye, target, fov, scale, image_name, png):
        """pbrt-v4's projection light at `eye` projecting the image toward `target` through a
        frustum of `fov` degrees over the image's shorter side, its top toward +y."""
        path = "textures/%s" % image_name
        self.files[path] = png
        z = normalize([t - e for t, e in zip(target, eye)])
        x = normalize(cross([0.0, 1.0, 0.0], z))
        y = cross(z, x)
        self._out().extend(["", "# " + name, "AttributeBegin",
                            "    ConcatTransform %s" % numbers([*x, 0.0, *y, 0.0, *z, 0.0, *eye, 1.0]),
                            '    LightSource "projection" "string filename" "%s" "float fov" %s '
                            '"float scale" %s' % (path, num(fov), num(scale)),
                            "AttributeEnd"])

    def goniometric_light(self, name, position, color, scale, image_name, intensity):
        """pbrt-v4's goniometric light at `position`: intensity(direction) (y up) written as its
        equal-area square, whose z is the light's y (pbrt-v4 swaps them)."""
        path = "textures/%s" % image_name

        def light(u, v):
            x, y, z = equal_area_square_to_sphere(u, v)
            return intensity((x, z, y))

        self.files[path] = rgbe_image(32, 32, light)
        self._out().extend(["", "# " + name, "AttributeBegin",
                            "    Translate %s %s %s" % tuple(num(c) for c in position),
                            '    LightSource "goniometric" "string filename" "%s" "rgb I" %s '
                            '"float scale" %s' % (path, rgb(color), num(scale)),
                            "AttributeEnd"])

    def environment(self, scene_name, sky):
        """pbrt-v4's infinite light: an equal-area square with z up, turned to y up."""
        path = "textures/%s-sky.hdr" % scene_name

        def world(u, v):
            x, y, z = equal_area_square_to_sphere(u, v)
            return sky((x, z, -y))  # Rotate -90 1 0 0: the map's +z is the world's +y

        self.files[path] = rgbe_image(256, 256, world)
        self.world += ["", "# the sky", "AttributeBegin", "    Rotate -90 1 0 0",
                       '    LightSource "infinite" "string filename" "%s"' % path, "AttributeEnd"]

    def begin_shared(self, name):
        self.shared = (name, [])

    def end_shared(self):
        name, lines = self.shared
        self.shared = None
        self.files[name + ".pbrt"] = ("# Shared by the scenes that Include it; written by scenes/generate_scenes.py.\n"
                                      + "\n".join(lines) + "\n").encode()
        self.world.append('Include "%s.pbrt"' % name)

    def write(self, path):
        folder = os.path.dirname(path)
        for relative, data in self.files.items():
            os.makedirs(os.path.dirname(os.path.join(folder, relative)) or folder, exist_ok=True)
            with open(os.path.join(folder, relative), "wb") as out:
                out.write(data)
        with open(path, "w") as out:
            out.write("\n".join(self.header + ["", "WorldBegin", ""] + self.world) + "\n")


def equal_area_square_to_sphere(u, v):
    """pbrt-v4's equal-area octahedral map (Clarberg 2008) of the unit square to the sphere."""
    u, v = 2 * u - 1, 2 * v - 1
    up, vp = abs(u), abs(v)
    signed_distance = 1 - (up + vp)
    r = 1 - abs(signed_distance)
    phi = (1 if r == 0 else (vp - up) / r + 1) * math.pi / 4
    z = math.copysign(1 - r * r, signed_distance)
    sin_theta = r * math.sqrt(max(0.0, 2 - r * r))
    return (math.copysign(math.cos(phi), u) * sin_theta, math.copysign(math.sin(phi), v) * sin_theta, z)


def lat_long_to_sphere(u, v):
    """photonfarm's latitude-longitude map: y up, the image's centre toward -z."""
    phi, theta = 2 * math.pi * (u - 0.5), math.pi * v
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def rgbe_image(width, height, radiance):
    """A Radiance .hdr of radiance(u, v) at each texel's centre, rows top to bottom, flat
    (uncompressed) scanlines."""
    rows = []
    for y in range(height):
        row = bytearray()
        for x in range(width):
            color = radiance((x + 0.5) / width, (y + 0.5) / height)
            brightest = max(color)
            if brightest < 1e-32:
                row += bytes(4)
                continue
            mantissa, exponent = math.frexp(brightest)
            scale = mantissa * 256.0 / brightest
            texel = bytes([min(255, int(c * scale)) for c in color] + [exponent + 128])
            # A flat scanline must not begin as a run-length one does (2, 2, then a byte < 128).
            if x == 0 and texel[0] == 2 and texel[1] == 2 and texel[2] < 128:
                texel = bytes([3]) + texel[1:]
            row += texel
        rows.append(bytes(row))
    header = "#?RADIANCE\n# written by scenes/generate_scenes.py\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width)
    return header.encode() + b"".join(rows)


def num(x):
    return repr(round(float(x), 9))


def numbers(values):
    return "[ " + " ".join(num(v) if isinstance(v, float) else str(v) for v in values) + " ]"


def rgb(color):
    return "[ " + " ".join(num(c) for c in color) + " ]"


def ply_mesh(positions, indices, normals):
    """A binary little-endian PLY of triangles with vertex normals."""
    header = ("ply\nformat binary_little_endian 1.0\ncomment written by scenes/generate_scenes.py\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n") % (
                  len(positions), len(indices) // 3)
    body = b"".join(struct.pack("<6f", *p, *n) for p, n in zip(positions, normals))
    body += b"".join(struct.pack("<B3i", 3, *indices[i:i + 3]) for i in range(0, len(indices), 3))
    return header.encode() + body


def ply_quads(quad_list):
    """A binary little-endian PLY of quads: float x y z vertices, uchar-counted int faces."""
    header = ("ply\nformat binary_little_endian 1.0\ncomment written by scenes/generate_scenes.py\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n") % (
                  4 * len(quad_list), len(quad_list))
    body = b"".join(struct.pack("<fff", *p) for quad in quad_list for p in quad)
    body += b"".join(struct.pack("<B4i", 4, 4 * q, 4 * q + 1, 4 * q + 2, 4 * q + 3) for q in range(len(quad_list)))
    return header.encode() + body
