#!/usr/bin/env python3
# fuzz: writes the seed corpora tests/fuzz/corpus/{obj,ply,image,scene}/ and the fixtures the
# scene seeds name (tests/fuzz/fixtures/). Python 3 standard library only; the JPEG seeds need
# cjpeg (Debian package libjpeg-turbo-progs) and are left as they are without it.
#
#   python3 tests/fuzz/make_corpus.py
#
# Image seeds have no file extension (the repository's .gitignore drops *.png); the loaders
# detect the format from the bytes.
import os
import shutil
import struct
import subprocess
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CORPUS = os.path.join(HERE, "corpus")
FIXTURES = os.path.join(HERE, "fixtures")


def write(folder, name, data):
    os.makedirs(folder, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


# OBJ: every face form, relative and forward indices, the tolerated layout quirks, a few errors.
OBJ = {
    "tri_v.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "quad_vt.obj": "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n",
    "quad_vn.obj": "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n",
    "pentagon_vtvn.obj": "v 0 0 0\nv 2 0 0\nv 2.5 1.5 0\nv 1 2.5 0\nv -0.5 1.5 0\n"
                         "vt 0 0\nvt 1 0\nvt 1 0.6\nvt 0.5 1\nvt 0 0.6\nvn 0 0 1\n"
                         "f 1/1/1 2/2/1 3/3/1 4/4/1 5/5/1\n",
    "negative.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                    "f -3/-3/-1 -2/-2/-1 -1/-1/-1\nv 1 1 0\nf -3 -1 -2\n",
    "forward.obj": "f 1 2 3\nf 3 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1e-3\n",
    "mixed_normals.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\n"
                         "f 1//1 2//1 3//1\nf 2 4 3\n",
    "layout.obj": "\ufeff# comment line\r\nmtllib scene.mtl\r\no thing\r\ng group_1\r\n"
                  "s off\r\nusemtl red\r\n\tv  0.0\t0.0  0.0 # trailing comment\r\n"
                  "v +1e0 -0.0 .5 1.0\r\nv 0 1 0 0.5 0.25 1\r\nvp 0.1 0.2\r\nvt 0 0 0\r\n"
                  "vt 1 0\r\nvt 0\r\nl 1 2\r\np 3\r\ncurv 0 1 1 2\r\n"
                  "f 1/1 2/2 3/3 # face\r\nf\t3/3  2/2\t1/1",
    "big_numbers.obj": "v 3.4e38 -3.4e38 1e-45\nv 1.17549435e-38 0 0\nv 0 1 0\nf 1 2 3\n",
    "err_index0.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
    "err_mixed_forms.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n",
    "err_range.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967296\n",
    "err_nan.obj": "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
}


# PLY --------------------------------------------------------------------------------------

def ply_header(fmt, elements, comments=()):
    lines = ["ply", "format %s 1.0" % fmt]
    lines += ["comment " + c for c in comments]
    for name, count, props in elements:
        lines.append("element %s %d" % (name, count))
        lines += ["property " + p for p in props]
    lines.append("end_header")
    return ("\n".join(lines) + "\n").encode()


QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


def ply_seeds():
    seeds = {}
    seeds["ascii_min.ply"] = ply_header("ascii", [
        ("vertex", 3, ["float x", "float y", "float z"]),
        ("face", 1, ["list uchar int vertex_indices"])]) + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
    body = "".join("%g %g %g 0 0 1 %g %g\n" % (x, y, z, x, y) for x, y, z in QUAD)
    seeds["ascii_normals_st.ply"] = ply_header("ascii", [
        ("vertex", 4, ["float32 x", "float32 y", "float32 z", "float nx", "float ny",
                       "float nz", "float s", "float t"]),
        ("face", 2, ["list uint8 int32 vertex_index", "uchar red"]),
        ("edge", 1, ["int vertex1", "int vertex2", "list uchar float weights"])],
        comments=["made by tests/fuzz/make_corpus.py"]).replace(
            b"end_header", b"obj_info blank lines follow\n\nend_header") + \
        (body + "\n3 0 1 2 255\n3 0 2 3 128\n0 1 2 0.5 0.25\n").encode()
    seeds["ascii_ints.ply"] = ply_header("ascii", [
        ("vertex", 4, ["char x", "short y", "int z", "uchar u", "ushort v"]),
        ("face", 1, ["list ushort uint vertex_indices"])]) + \
        b"-1 0 5 0 0\n1 -32768 5 255 0\n1 32767 -7 255 65535\n-1 2 0 0 65535\n4 0 1 2 3\n"

    # binary little endian, fixed-size float vertices (the memcpy fast path), uvs, extra face data
    verts = b"".join(struct.pack("<8f", x, y, z, 0, 0, 1, x, y) for x, y, z in QUAD)
    faces = struct.pack("<B3IB", 3, 0, 1, 2, 7) + struct.pack("<B4IB", 4, 0, 1, 2, 3, 9)
    seeds["binary_le_float.ply"] = ply_header("binary_little_endian", [
        ("vertex", 4, ["float x", "float y", "float z", "float nx", "float ny", "float nz",
                       "float texture_u", "float texture_v"]),
        ("face", 2, ["list uchar uint vertex_indices", "uchar flags"])]) + verts + faces + b"junk"

    # binary big endian, doubles and 16-bit indices
    verts = b"".join(struct.pack(">3d", x, y, z) for x, y, z in QUAD)
    faces = struct.pack(">B3H", 3, 0, 1, 2) + struct.pack(">B3H", 3, 0, 2, 3)
    seeds["binary_be_double.ply"] = ply_header("binary_big_endian", [
        ("vertex", 4, ["double x", "double y", "double z"]),
        ("face", 2, ["list uint8 uint16 vertex_indices"])]) + verts + faces

    # binary, variable-size vertices (a list property), integer coordinates, other elements
    # before and after, the face element before the vertex element
    material = struct.pack("<Bf", 2, 0.5)
    faces = struct.pack("<i3i", 3, 0, 1, 2) + struct.pack("<i4i", 4, 3, 2, 1, 0)
    verts = b"".join(struct.pack("<hbB", x, y, z) + struct.pack("<B2H", 2, 7, 8) for x, y, z in
                     [(0, 0, 0), (300, 0, 0), (300, 100, 0), (0, 100, 0)])
    seeds["binary_le_mixed.ply"] = ply_header("binary_little_endian", [
        ("material", 1, ["uchar id", "float shininess"]),
        ("face", 2, ["list int int vertex_indices"]),
        ("vertex", 4, ["short x", "char y", "uchar z", "list uchar ushort tags"]),
        ("extra", 2, ["list uint char data"])]) + material + faces + verts + \
        struct.pack("<I", 0) + struct.pack("<I2b", 2, -1, 1)

    # binary big endian, float vertices without the fast path (byte swap), int8 counts
    verts = b"".join(struct.pack(">3f", x, y, z) for x, y, z in QUAD)
    faces = struct.pack(">b4i", 4, 0, 1, 2, 3)
    seeds["binary_be_float.ply"] = ply_header("binary_big_endian", [
        ("vertex", 4, ["float32 x", "float32 y", "float32 z"]),
        ("face", 1, ["list int8 int32 vertex_indices"])]) + verts + faces

    seeds["err_truncated.ply"] = seeds["binary_le_float.ply"][:-20]
    seeds["err_count.ply"] = ply_header("binary_little_endian", [
        ("vertex", 4000000000, ["float x", "float y", "float z"]),
        ("face", 1, ["list uchar int vertex_indices"])]) + verts
    return seeds


# Images -----------------------------------------------------------------------------------

def png_chunk(kind, data):
    return struct.pack(">I", len(data)) + kind + data + \
        struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)


def png(width, height, bit_depth, colour_type, rows, interlace=0, extra=b"", filters=None):
    """rows: list of raw scanline bytes (without filter byte), already in pass order when
    interlaced; filters: filter type per row (only 0 = none and 1 = sub are computed)."""
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[colour_type]
    bpp = max(1, channels * bit_depth // 8)
    raw = b""
    for i, row in enumerate(rows):
        f = filters[i] if filters else 0
        if f == 1:
            row = bytes((row[j] - (row[j - bpp] if j >= bpp else 0)) & 0xFF
                        for j in range(len(row)))
        raw += bytes([f]) + row
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, colour_type, 0, 0, interlace)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + extra +
            png_chunk(b"IDAT", zlib.compress(raw, 9)) + png_chunk(b"IEND", b""))


def adam7_rows(width, height, pixel):
    """Scanlines of an Adam7-interlaced 8-bit RGB image, pass by pass."""
    passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2),
              (0, 1, 1, 2)]
    rows = []
    for x0, y0, dx, dy in passes:
        xs = range(x0, width, dx)
        if not xs:
            continue
        for y in range(y0, height, dy):
            rows.append(b"".join(pixel(x, y) for x in xs))
    return rows


def rgb(x, y):
    return bytes([(40 * x) & 255, (60 * y) & 255, (x * y * 17) & 255])


def hdr(width, height, pixels, rle):
    out = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n-Y %d +X %d\n" % (height, width)
    for y in range(height):
        line = pixels[y * width:(y + 1) * width]
        if not rle:
            out += b"".join(bytes(p) for p in line)
            continue
        out += bytes([2, 2, width >> 8, width & 255])
        for c in range(4):  # one run, then literals
            values = [p[c] for p in line]
            out += bytes([128 + 4, values[0]])
            out += bytes([width - 4]) + bytes(values[4:])
    return out


def image_seeds():
    seeds = {}
    seeds["png_grey8_3x2"] = png(3, 2, 8, 0, [b"\x00\x80\xff", b"\x10\x20\x30"])
    seeds["png_grey_alpha8_2x2"] = png(2, 2, 8, 4, [b"\x00\xff\x80\x80", b"\xff\x00\x40\x10"])
    seeds["png_rgb8_4x3_filters"] = png(4, 3, 8, 2, [b"".join(rgb(x, y) for x in range(4))
                                                    for y in range(3)], filters=[0, 1, 0])
    seeds["png_rgba8_2x2"] = png(2, 2, 8, 6, [b"\xff\x00\x00\xff\x00\xff\x00\x80",
                                              b"\x00\x00\xff\x00\xff\xff\xff\xff"])
    seeds["png_rgb16_2x2"] = png(2, 2, 16, 2, [b"\xff\xff\x00\x00\x80\x00" * 2,
                                               b"\x00\x01\x12\x34\xff\xfe" * 2])
    seeds["png_grey16_2x1"] = png(2, 1, 16, 0, [b"\x00\x00\xff\xff"])
    seeds["png_grey1_9x2"] = png(9, 2, 1, 0, [b"\xaa\x80", b"\x55\x00"])
    plte = png_chunk(b"PLTE", b"\xff\x00\x00\x00\xff\x00\x00\x00\xff")
    trns = png_chunk(b"tRNS", b"\xff\x80")
    seeds["png_palette_3x2"] = png(3, 2, 8, 3, [b"\x00\x01\x02", b"\x02\x01\x00"],
                                   extra=plte + trns)
    seeds["png_adam7_rgb8_9x9"] = png(9, 9, 8, 2, adam7_rows(9, 9, rgb), interlace=1)
    pixels = [(128 + i % 64, 64, 32 + i % 3, 128 + i % 4) for i in range(16 * 2)]
    seeds["hdr_flat_2x2"] = hdr(2, 2, pixels[:4], rle=False)
    seeds["hdr_rle_16x2"] = hdr(16, 2, pixels, rle=True)
    seeds["hdr_old_rle_8x1"] = (b"#?RGBE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 8\n" +
                                bytes([128, 64, 32, 129]) + bytes([1, 1, 1, 7]))
    if shutil.which("cjpeg"):
        width, height = 16, 16
        ppm = b"P6\n%d %d\n255\n" % (width, height) + b"".join(
            rgb(x, y) for y in range(height) for x in range(width))
        pgm = b"P5\n%d %d\n255\n" % (width, height) + bytes(
            (x * 16 + y) & 255 for y in range(height) for x in range(width))
        variants = {
            "jpeg_420_16x16": (ppm, ["-quality", "50"]),
            "jpeg_444_16x16": (ppm, ["-quality", "90", "-sample", "1x1"]),
            "jpeg_progressive_16x16": (ppm, ["-progressive"]),
            "jpeg_restart_16x16": (ppm, ["-restart", "1B", "-optimize"]),
            "jpeg_grey_16x16": (pgm, ["-grayscale"]),
        }
        for name, (source, args) in variants.items():
            seeds[name] = subprocess.run(["cjpeg"] + args, input=source, check=True,
                                         capture_output=True).stdout
    return seeds


# Scenes -----------------------------------------------------------------------------------

SCENE_FEATURES = """{
  "version": 1,
  "description": "every key the loader knows, with the fixture files",
  "camera": {"position": [0, 1, -5], "look_at": [0, 0.5, 0], "up": [0, 1, 0], "fov_deg": 60,
             "fov_axis": "horizontal", "resolution": [64, 48], "spp": 2},
  "background": [0.05, 0.05, 0.1],
  "environment": "tex.hdr",
  "shading": {"brdf": "report", "max_reflection_depth": 3, "max_refraction_depth": 2,
              "local": true, "reflection": true, "refraction": false, "fresnel": false,
              "reflected_color": [1, 0, 1]},
  "tonemap": "report",
  "materials": {
    "default": {"c_d": [0.5, 0.5, 0.5]},
    "ward": {"model": "ward", "alpha": 0.2, "c_s": [1, 1, 1], "k_s": 0.4, "glossy_samples": 4},
    "duer": {"model": "ward-duer", "alpha": 0.3},
    "blinn": {"model": "blinn-phong", "exponent": 80},
    "glossy": {"model": "glossy-phong", "exponent": 30, "glossy_samples": 8},
    "textured": {"texture": {"file": "tex_8bit.img", "filter": "nearest", "encoding": "srgb",
                             "repeat": false}, "texture_specular": true,
                 "normal_map": "tex_8bit.img", "normal_map_mode": "replace"},
    "checker": {"texture": {"checker": [[1, 1, 1], [0, 0, 0]], "checks": 4}},
    "mirror": {"reflection": 0.9, "k_a_after": 0.1, "fresnel": false, "env_map": "tex.hdr"},
    "glass": {"refraction": {"ior": 1.5, "filter": [0.9, 0.95, 1]}},
    "lamp": {"emission": [4, 4, 3]}
  },
  "objects": [
    {"shape": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "checker"},
    {"shape": "sphere", "center": [-1, 1, 0], "radius": 1, "material": "glass"},
    {"shape": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "ward",
     "transform": {"translate": [1, 0, 0], "rotate_deg": [10, 20, 30], "scale": [1, 2, 0.5]}},
    {"shape": "cylinder", "radius": 0.25, "height": 1, "material": "mirror",
     "transform": {"rotate": [{"axis": "x", "deg": 90}, {"axis": "z", "deg": -45}], "scale": 2}},
    {"shape": "triangle", "vertices": [[0, 0, 3], [1, 0, 3], [0, 1, 3]], "material": "duer"},
    {"shape": "mesh", "file": "tri.obj", "material": "textured", "normals": "file",
     "fit": {"size": 2, "axis": "longest", "offset": [0, 0.5, 0]}},
    {"shape": "mesh", "file": "quad.ply", "material": "blinn", "normals": "flat",
     "fit": {"scale": 0.5}, "transform": {"translate": [0, 2, 0]}},
    {"shape": "mesh", "file": "tri.obj", "normals": "smooth"},
    {"shape": "sphere", "radius": 0.1, "material": "lamp", "transform": {"translate": [0, 3, 0]}}
  ],
  "lights": [
    {"type": "point", "position": [-3, 5, -4], "color": [1, 0.9, 0.8], "intensity": 40},
    {"type": "directional", "direction": [1, 1, -1], "intensity": 0.5, "shadows": false},
    {"type": "rect", "corner": [-1, 4, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2],
     "intensity": 10, "samples": 4, "visible": true},
    {"type": "disk", "center": [0, 4, 0], "normal": [0, -1, 0], "radius": 0.5, "samples": 2,
     "visible": false},
    {"type": "box", "min": [2, 3, 2], "max": [2.5, 3.5, 2.5], "color": [0.5, 0.5, 1]}
  ]
}
"""

SCENE_SMALL = {
    "minimal.json": '{"camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 45}}\n',
    "mesh_ply.json": '{"camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov_deg": 90},\n'
                     ' "objects": [{"shape": "mesh", "file": "quad.ply", "fit": {"size": 1}}]}\n',
    "err_duplicate.json": '{"camera": {"fov_deg": 1, "fov_deg": 2}}\n',
    "err_syntax.json": '{"camera": {"position": [0, 0, 0,], "look_at": [0, 0, 1e400]}}\n',
    "unicode.json": '{"description": "\\u00e9\\ud83d\\ude00\\n", "camera": {"position": [0, 0, 0],'
                    ' "look_at": [0, 0, 1], "fov_deg": 179.9, "up": [1e-30, 1, 0]},'
                    ' "materials": {"\\u0000 odd name": {"k_d": 0}}}\n',
}


def scene_seeds():
    seeds = {"features.json": SCENE_FEATURES}
    seeds.update(SCENE_SMALL)
    # The repository's scenes, with the shared models replaced by the fixtures and the words that
    # make fuzz_scene skip an input (see names_large_model there) taken out.
    replace = {"bunny.ply": "quad.ply", "dragon.ply": "tri.obj", "dragon.obj": "tri.obj",
               "Stanford bunny": "mesh", "Stanford dragon": "mesh", "bunny": "mesh",
               "dragon": "mesh", "Dragon": "Mesh"}
    scenes = os.path.join(ROOT, "scenes")
    for name in sorted(os.listdir(scenes)) if os.path.isdir(scenes) else []:
        if not name.endswith(".json"):
            continue
        with open(os.path.join(scenes, name)) as f:
            text = f.read()
        for a, b in replace.items():
            text = text.replace(a, b)
        if any(w in text for w in ("shared", "bunny", "dragon", "apple", "ornell")):
            continue
        if len(text) <= 16384:
            seeds["scenes_" + name] = text
    return seeds


def fixtures():
    write(FIXTURES, "tri.obj", "# fuzz fixture: one triangle with uvs and normals\n"
          "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n")
    body = "".join("%g %g %g 0 0 1 %g %g\n" % (x, y, z, x, y) for x, y, z in QUAD)
    write(FIXTURES, "quad.ply", ply_header("ascii", [
        ("vertex", 4, ["float x", "float y", "float z", "float nx", "float ny", "float nz",
                       "float u", "float v"]),
        ("face", 1, ["list uchar int vertex_indices"])],
        comments=["fuzz fixture: a unit quad with normals and uvs"]) + (body + "4 0 1 2 3\n").encode())
    write(FIXTURES, "tex_8bit.img", png(2, 2, 8, 2, [b"\xff\x00\x00\x00\xff\x00",
                                                     b"\x00\x00\xff\xff\xff\xff"]))
    write(FIXTURES, "tex.hdr", hdr(2, 2, [(128, 64, 32, 129), (10, 20, 30, 128), (0, 0, 0, 0),
                                          (200, 200, 200, 127)], rle=False))


def main():
    fixtures()
    for kind, seeds in (("obj", OBJ), ("ply", ply_seeds()), ("image", image_seeds()),
                        ("scene", scene_seeds())):
        folder = os.path.join(CORPUS, kind)
        for name, data in seeds.items():
            write(folder, name, data)
        print("%-6s %3d seeds in %s" % (kind, len(seeds), os.path.relpath(folder, ROOT)))


if __name__ == "__main__":
    main()
