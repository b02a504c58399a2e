#!/usr/bin/env python3
"""make_corpus.py DIR: writes lightpass's own corpus of bad input files into DIR, and DIR/manifest.json
listing every case: the lightpass arguments, what must happen (a one-line error naming the file and
what is wrong, or a documented fallback with a warning) and which class of the bad-input promise
(README, "Bad input") it checks. run_corpus.py runs them.

Placeholders in the manifest: {C} is DIR, {O} a fresh empty output folder per case; in regexes {C}
stands for DIR, escaped."""
import base64, json, os, shutil, struct, sys, zlib

C = os.path.abspath(sys.argv[1])
shutil.rmtree(C, ignore_errors=True)
os.makedirs(C)
cases = []


def write(name, data):
    path = os.path.join(C, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)
    return path


def fifo(name):
    os.mkfifo(os.path.join(C, name))


def case(cls, name, args, expect, regex, **extra):
    cases.append(dict(cls=cls, name=name, args=args, expect=expect, regex=regex, **extra))


RENDER = ["--size", "32x24", "--frames", "1", "--warmup", "0"]
ENV_SMALL = ["--env-size", "16", "--ibl-specular-size", "8", "--ibl-specular-levels", "4"]  # quick on llvmpipe


def render_scene(scene, out="{O}/out.png", more=()):
    return ["render", "--scene", "{C}/" + scene, "--out", out, *RENDER, *more]


def render_model(model, out="{O}/out.png"):
    # A bare model is lit by the bundled studio environment: its bake kept small too.
    return ["render", "--model", model if model.startswith("/") else "{C}/" + model, "--out", out, *RENDER, *ENV_SMALL]


# ---- well-formed pieces the bad ones are built around --------------------------------------------
CUBE_OBJ = """v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1
vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1
f 1/1 4/4 3/3 2/2\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\nf 4/4 8/1 7/2 3/3\nf 1/1 5/2 8/3 4/4\nf 2/1 3/2 7/3 6/4
"""
LIGHT = {"type": "directional", "direction": [-0.3, -1, -0.5], "intensity": 3}
CAMERA = {"position": [3, 2, 4], "target": [0, 0, 0]}


def scene(name, **fields):
    body = {"camera": CAMERA, "models": [{"primitive": "cube"}], "lights": [LIGHT]}
    body.update(fields)
    return write(name, json.dumps(body))


def png(width, height, rgba=None):
    """An RGBA8 PNG; rgba(x, y) -> 4 bytes, or a grey gradient."""
    raw = bytearray()
    for y in range(height):
        raw.append(0)
        for x in range(width):
            raw += rgba(x, y) if rgba else bytes(((x * 37 + y * 11) & 255, 128, 64, 255))
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(bytes(raw))) + chunk(b"IEND", b""))


def radiance(width, height):
    # Flat (not run-length) RGBE scanlines: the first pixel is not the 2,2 RLE marker.
    header = f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n".encode()
    return header + bytes((128, 128, 128, 129)) * (width * height)


def exr(data_window, display_window, value=0.5, channels=("R", "G", "B")):
    """An uncompressed scanline EXR with float `channels` (all `value`) over data_window (x0, y0, x1, y1)."""
    def attr(name, kind, body):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(body)) + body
    channels = sorted(channels)  # a chlist is in name order
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in channels) + b"\0"
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", struct.pack("<4i", *data_window)) +
              attr("displayWindow", "box2i", struct.pack("<4i", *display_window)) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)) + attr("screenWindowWidth", "float", struct.pack("<f", 1)) +
              b"\0")
    width, height = data_window[2] - data_window[0] + 1, data_window[3] - data_window[1] + 1
    n = len(channels)
    lines = [struct.pack("<ii", data_window[1] + y, n * 4 * width) + struct.pack(f"<{n * width}f", *([value] * n * width))
             for y in range(height)]
    offset, table = len(header) + 8 * height, b""
    for line in lines:
        table += struct.pack("<Q", offset)
        offset += len(line)
    return header + table + b"".join(lines)


write("cube.obj", CUBE_OBJ)
write("textured.mtl", "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n")
write("tex.png", png(8, 8))

# ---- 1. special files: one regular-file check, naming the file --------------------------------------
fifo("fifo.obj")
fifo("fifo.json")
fifo("fifo.mtl")
fifo("fifo.png")
fifo("fifo.hdr")
os.makedirs(os.path.join(C, "folder.obj"))
os.makedirs(os.path.join(C, "folder.json"))
os.makedirs(os.path.join(C, "folder.hdr"))
case(1, "fifo_model", render_model("fifo.obj"), "error", r"{C}/fifo.obj: is a FIFO, not a regular file")
case(1, "fifo_scene", render_scene("fifo.json"), "error", r"{C}/fifo.json: is a FIFO, not a regular file")
scene("scene_fifo_obj.json", models=[{"obj": "fifo.obj"}])
case(1, "fifo_scene_obj", render_scene("scene_fifo_obj.json"), "error",
     r"scene_fifo_obj.json: models\[0\]\.obj: {C}/fifo.obj: is a FIFO")
write("mtllib_fifo.obj", "mtllib fifo.mtl\n" + CUBE_OBJ)
case(1, "fifo_mtllib", render_model("mtllib_fifo.obj"), "error", r"mtllib_fifo.obj: mtllib {C}/fifo.mtl: is a FIFO")
case(1, "dev_zero_model", render_model("/dev/zero"), "error", r"/dev/zero: is a character device, not a regular file")
case(1, "dev_zero_scene", ["render", "--scene", "/dev/zero", "--out", "{O}/out.png", *RENDER], "error",
     r"/dev/zero: is a character device, not a regular file")
case(1, "folder_model", render_model("folder.obj"), "error", r"{C}/folder.obj: is a folder, not an OBJ file")
case(1, "folder_scene", render_scene("folder.json"), "error", r"{C}/folder.json: is a folder, not a scene file")
write("texture_fifo.obj", "mtllib texture_fifo.mtl\nusemtl m\n" + CUBE_OBJ)
write("texture_fifo.mtl", "newmtl m\nmap_Kd fifo.png\n")
case(1, "fifo_texture", render_model("texture_fifo.obj"), "fallback",
     r"warning: {C}/fifo.png: is a FIFO, not a regular file; using a checker texture", outputs=["{O}/out.png"])
scene("env_fifo.json", environment={"map": "fifo.hdr"})
case(1, "fifo_environment", render_scene("env_fifo.json", more=[*ENV_SMALL]), "error",
     r"{C}/fifo.hdr: is a FIFO, not a regular file")
scene("env_folder.json", environment={"map": "folder.hdr"})
case(1, "folder_environment", render_scene("env_folder.json", more=[*ENV_SMALL]), "error",
     r"{C}/folder.hdr: is a folder")

# ---- 2. outputs are all or nothing ------------------------------------------------------------------
scene("plain.json")
case(2, "exr_unwritable_no_png", render_scene("plain.json", more=["--exr", "{O}/missing/x.exr"]), "error",
     r"{O}/missing/x.exr: folder .* does not exist", absent=["{O}/out.png"])
os.makedirs(os.path.join(C, "is_a_folder.json"))
case(2, "timings_json_folder_no_png", render_scene("plain.json", more=["--timings-json", "{C}/is_a_folder.json"]),
     "error", r"is_a_folder.json: is a folder, not a file name", absent=["{O}/out.png"])
case(2, "same_output_twice", render_scene("plain.json", more=["--timings-json", "{O}/out.png"]), "error",
     r"out.png: named twice as an output", absent=["{O}/out.png"])
# A full disk: the process may write no more than 100 bytes per file (RLIMIT_FSIZE).
case(2, "full_disk_png", render_scene("plain.json", out="{O}/big.png", more=["--size", "64x48"]), "error",
     r"{O}/big.png: cannot write: File too large", fsize_limit=100, absent=["{O}/big.png"])
case(2, "full_disk_exr", ["render", "--scene", "{C}/plain.json", "--exr", "{O}/big.exr", *RENDER], "error",
     r"{O}/big.exr: cannot write: File too large", fsize_limit=100, absent=["{O}/big.exr"])
case(2, "sweep_csv_folder_no_images",
     ["sweep", "--scene", "{C}/plain.json", "--knob", "shadow-size", "--size", "32x24", "--frames", "1", "--warmup", "0",
      "--out-dir", "{O}/sweep"], "error", r"{O}/sweep/sweep.csv: is a folder, not a file name",
     make_dirs=["{O}/sweep/sweep.csv"], absent=["{O}/sweep/shadow-size/reference.png", "{O}/sweep/shadow-size/0.png"])
write("a_file", "not a folder\n")
case(2, "sweep_out_dir_under_file",
     ["sweep", "--scene", "{C}/plain.json", "--knob", "shadow-size", "--size", "32x24", "--out-dir", "{C}/a_file/sweep"],
     "error", r"a_file/sweep/shadow-size: cannot create the output folder")
case(2, "bench_json_unwritable",
     ["bench", "--scene", "{C}/plain.json", "--size", "32x24", "--frames", "1", "--warmup", "0",
      "--vary", "--shadow-size 64,128", "--timings-json", "{O}/missing/bench.json"], "error",
     r"{O}/missing/bench.json: folder .* does not exist")
case(2, "graph_dot_unwritable", ["graph", "--scene", "{C}/plain.json", "--dot", "{O}/missing/g.dot"], "error",
     r"{O}/missing/g.dot: folder .* does not exist")

# ---- 3. GPU limits ----------------------------------------------------------------------------------
# 32769 texels: over GL_MAX_TEXTURE_SIZE on every GPU we know (llvmpipe 16384, NVIDIA 32768).
write("wide.png", png(32769, 2, lambda x, y: b"\xc0\x80\x40\xff"))
write("wide_texture.obj", "mtllib wide_texture.mtl\nusemtl m\n" + CUBE_OBJ)
write("wide_texture.mtl", "newmtl m\nKd 1 1 1\nmap_Kd wide.png\n")
case(3, "texture_over_max_size", render_model("wide_texture.obj"), "fallback",
     r"warning: {C}/wide.png: 32769x2 is larger than this GPU's [0-9]+ texel limit \(GL_MAX_TEXTURE_SIZE\); downscaled to",
     outputs=["{O}/out.png"], forbid=r"GL:|error")
write("wide.hdr", radiance(32769, 2))
scene("env_wide.json", environment={"map": "wide.hdr"})
case(3, "environment_over_max_size", render_scene("env_wide.json", more=[*ENV_SMALL]), "fallback",
     r"warning: {C}/wide.hdr: 32769x2 is larger than this GPU's [0-9]+ texel limit", outputs=["{O}/out.png"],
     forbid=r"GL:|error")
# LIGHTPASS_GPU_FREE_BYTES stands in for a GPU with 64 MiB free (the real limit differs per machine).
case(3, "size_over_gpu_memory",
     ["render", "--scene", "{C}/plain.json", "--out", "{O}/out.png", "--size", "2048x2048", "--frames", "1", "--warmup", "0"],
     "error", r"--size 2048x2048: the frame's render targets need [0-9.]+ GiB, more than the 0.06 GiB this GPU has free",
     env={"LIGHTPASS_GPU_FREE_BYTES": str(64 << 20)}, absent=["{O}/out.png"])

# ---- 4. numbers the OBJ parser used to turn into zero -----------------------------------------------
write("nan_vertex.obj", CUBE_OBJ + "v nan 7 7\nf 1 2 9\n")
case(4, "nan_vertex", render_model("nan_vertex.obj"), "fallback",
     r"nan_vertex.obj:19: 1 vertices with NaN, Inf or beyond \+-1e18 coordinates \(first here\); their triangles are dropped",
     outputs=["{O}/out.png"])
write("huge_vertex.obj", CUBE_OBJ + "v 1e30 0 0\nf 1 2 9\n")
case(4, "vertex_1e30", render_model("huge_vertex.obj"), "fallback",
     r"huge_vertex.obj:19: 1 vertices with NaN, Inf or beyond \+-1e18 coordinates", outputs=["{O}/out.png"])
write("letters_vertex.obj", "v 0 0 0\nv 1 0 0\nv a b c\nf 1 2 3\n")
case(4, "letters_vertex", render_model("letters_vertex.obj"), "error", r"letters_vertex.obj:3: v: 'a' is not a number")
write("short_vertex.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n")
case(4, "short_vertex", render_model("short_vertex.obj"), "error", r"short_vertex.obj:2: v needs 3 numbers, got 2")
write("trailing_junk.obj", "v 0 0 0\nv 1 0 0x\nv 0 1 0\nf 1 2 3\n")
case(4, "trailing_junk", render_model("trailing_junk.obj"), "error", r"trailing_junk.obj:2: v: '0x' is not a number")
write("huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4294967299\n")
case(4, "index_over_int", render_model("huge_index.obj"), "error", r"huge_index.obj:5: index 4294967299 is out of range")
write("word_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n")
case(4, "word_index", render_model("word_index.obj"), "error", r"word_index.obj:4: 'three' is not a vertex index")
write("nan_kd.obj", "mtllib nan_kd.mtl\nusemtl m\n" + CUBE_OBJ)
write("nan_kd.mtl", "newmtl m\nKd nan nan nan\nNs abc\n")
case(4, "nan_kd", render_model("nan_kd.obj"), "fallback",
     r"nan_kd.mtl:2: Kd: 'nan' is not a finite number; using the default 0.8 0.8 0.8.*nan_kd.mtl:3: Ns: 'abc' is not a number",
     outputs=["{O}/out.png"])
# A glass material (illum 7: refraction) with an index below 1 (3ds Max writes Ni 0.001): no bend, one
# warning naming the material; the model renders through the transmission path.
write("glass_low_ni.obj", "mtllib glass_low_ni.mtl\nusemtl glass\n" + CUBE_OBJ)
write("glass_low_ni.mtl", "newmtl glass\nKd 0.01 0.01 0.01\nTf 0.9 0.9 0.9\nNi 0.001\nillum 7\n")
case(4, "mtl_glass_low_ni", render_model("glass_low_ni.obj"), "fallback",
     r"glass_low_ni.obj: material 'glass': Ni 0.001 is below 1 \(or not finite\); its refraction bends no ray \(Ni 1\)",
     outputs=["{O}/out.png"])
write("nan_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn nan 0 1\nf 1//1 2//1 3//1\n")
case(4, "nan_normal", render_model("nan_normal.obj"), "fallback",
     r"nan_normal.obj:4: 1 normals or texture coordinates with NaN or Inf \(first here\) ignored", outputs=["{O}/out.png"])

# ---- 5. degenerate triangles judged by their own size -----------------------------------------------
# A 5 mm cube (the cube scaled to +-2.5 mm) beside a 20 km ground quad.
small_and_huge = "".join(" ".join(["v"] + ["%g" % (0.0025 * float(t)) for t in l.split()[1:]]) + "\n"
                         if l.startswith("v ") else l + "\n" for l in CUBE_OBJ.splitlines())
small_and_huge += "v -10000 -1 -10000\nv 10000 -1 -10000\nv 10000 -1 10000\nv -10000 -1 10000\nf 9 12 11 10\n"
write("mm_cube_km_plane.obj", small_and_huge)
case(5, "mm_cube_beside_km_plane", render_model("mm_cube_km_plane.obj"), "ok", r"wrote ", outputs=["{O}/out.png"],
     forbid=r"degenerate|dropped")
write("stray_vertex.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1e15 1e15 1e15\nf 1 2 3 4\n")
case(5, "quad_beside_stray_vertex", render_model("stray_vertex.obj"), "ok", r"wrote ", outputs=["{O}/out.png"],
     forbid=r"degenerate|dropped|no triangles")

# ---- 6. text details --------------------------------------------------------------------------------
write("bom.obj", "\ufeffv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
case(6, "bom_obj", render_model("bom.obj"), "ok", r"wrote ", outputs=["{O}/out.png"], forbid=r"warning|error")
write("bom_scene.json", "\ufeff" + json.dumps({"camera": CAMERA, "models": [{"obj": "bom.obj"}], "lights": [LIGHT]}))
case(6, "bom_scene", render_scene("bom_scene.json"), "ok", r"wrote ", outputs=["{O}/out.png"], forbid=r"warning|error")
write("no_mtl.obj", "mtllib nowhere.mtl\n" + CUBE_OBJ)
write("five_hundred.json", json.dumps({"camera": CAMERA, "lights": [LIGHT],
                                       "models": [{"obj": "no_mtl.obj", "translate": [i % 25, 0, i // 25]} for i in range(500)]}))
# 500 models naming one OBJ: the file is parsed once, so its warning is said once (the log's own
# collapsing of repeated lines is tested in unit_tests' Log.*).
case(6, "warning_once_for_500_models", ["graph", "--scene", "{C}/five_hundred.json"], "fallback",
     r"nowhere.mtl: file not found; using default materials", max_warnings=1, forbid=r"Failed to load|repeated")
write("plane_x.obj", "v 2 -1 -1\nv 2 1 -1\nv 2 1 1\nv 2 -1 1\nf 1 2 3 4\nf 1 4 3 2\n")
case(6, "model_in_plane_x_const", render_model("plane_x.obj"), "ok", r"wrote ", outputs=["{O}/out.png"],
     covered=["{O}/out.png", 0.1])

# ---- 7. images: truncation and corruption -----------------------------------------------------------
good = png(16, 16)
idat = good.index(b"IDAT")
corrupt = bytearray(good)
corrupt[idat + 10] ^= 0x55  # inside the compressed data; the CRC no longer matches
write("corrupt.png", bytes(corrupt))
write("truncated.png", good[:len(good) // 2])
for name in ("corrupt", "truncated"):
    write(name + "_texture.obj", f"mtllib {name}_texture.mtl\nusemtl m\n" + CUBE_OBJ)
    write(name + "_texture.mtl", f"newmtl m\nKd 1 1 1\nmap_Kd {name}.png\n")
case(7, "png_corrupt_idat", render_model("corrupt_texture.obj"), "fallback",
     r"warning: {C}/corrupt.png: corrupt: CRC mismatch in chunk IDAT at byte [0-9]+; using a checker texture",
     outputs=["{O}/out.png"])
case(7, "png_truncated", render_model("truncated_texture.obj"), "fallback",
     r"warning: {C}/truncated.png: truncated: chunk IDAT at byte [0-9]+ needs [0-9]+ bytes.*; using a checker texture",
     outputs=["{O}/out.png"])
hdr = radiance(16, 8)
write("truncated.hdr", hdr[:len(hdr) - 100])
scene("env_truncated.json", environment={"map": "truncated.hdr"})
case(7, "hdr_truncated", render_scene("env_truncated.json", more=[*ENV_SMALL]), "error",
     r"{C}/truncated.hdr: truncated: the decoder needed more than the file's [0-9]+ bytes", absent=["{O}/out.png"])
write("sparse.exr", exr((0, 0, 1, 0), (0, 0, 16383, 8191)))
scene("env_sparse_exr.json", environment={"map": "sparse.exr"})
case(7, "exr_display_window_huge", render_scene("env_sparse_exr.json", more=[*ENV_SMALL]), "error",
     r"{C}/sparse.exr: display window 16384x8192 is [0-9]+ times the 2x1 data window", timeout=10,
     absent=["{O}/out.png"])
write("small.exr", exr((0, 0, 3, 1), (0, 0, 3, 1)))
write("truncated.exr", open(os.path.join(C, "small.exr"), "rb").read()[:-20])
scene("env_truncated_exr.json", environment={"map": "truncated.exr"})
case(7, "exr_truncated", render_scene("env_truncated_exr.json", more=[*ENV_SMALL]), "error",
     r"{C}/truncated.exr: ", absent=["{O}/out.png"])

# A map that is not 2:1 is read as latitude-longitude all the same (stretched), with a warning.
write("square.hdr", radiance(8, 8))
scene("env_square.json", environment={"map": "square.hdr"})
case(7, "hdr_not_two_to_one", render_scene("env_square.json", more=[*ENV_SMALL, "--ibl"]), "fallback",
     r"warning: {C}/square.hdr: 8x8 is not 2:1; read as an equirectangular \(latitude-longitude\) map, stretched",
     outputs=["{O}/out.png"], max_warnings=1)
# Negative texels: replaced with one warning, the map decoded once for the cube and the IBL bake.
write("negative.exr", exr((0, 0, 7, 3), (0, 0, 7, 3), value=-0.25))
scene("env_negative_exr.json", environment={"map": "negative.exr"})
case(7, "exr_negative_texels_warned_once", render_scene("env_negative_exr.json", more=[*ENV_SMALL, "--ibl"]), "fallback",
     r"warning: {C}/negative.exr: replaced 96 negative, 0 NaN and 0 \+Inf texel components", outputs=["{O}/out.png"],
     max_warnings=1)

# EXR channels: a luminance image (Y) is grey; a renderer's multi-layer file without bare R, G, B is
# read from its first layer holding them, named in a warning; no colour at all is an error.
write("luminance.exr", exr((0, 0, 7, 3), (0, 0, 7, 3), channels=("Y",)))
scene("env_luminance_exr.json", environment={"map": "luminance.exr"})
case(7, "exr_luminance_is_grey", render_scene("env_luminance_exr.json", more=[*ENV_SMALL]), "ok", r"wrote ",
     outputs=["{O}/out.png"], forbid=r"warning|error")
write("layers.exr", exr((0, 0, 7, 3), (0, 0, 7, 3), channels=("ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                                               "ViewLayer.Combined.A", "ViewLayer.Depth.Z")))
scene("env_layers_exr.json", environment={"map": "layers.exr"})
case(7, "exr_layer_named", render_scene("env_layers_exr.json", more=[*ENV_SMALL]), "fallback",
     r"warning: {C}/layers.exr: no R, G, B channels; read layer 'ViewLayer.Combined' \(layers with R, G and B: ViewLayer.Combined\)",
     outputs=["{O}/out.png"])
write("depth_only.exr", exr((0, 0, 7, 3), (0, 0, 7, 3), channels=("Z",)))
scene("env_depth_exr.json", environment={"map": "depth_only.exr"})
case(7, "exr_no_colour", render_scene("env_depth_exr.json", more=[*ENV_SMALL]), "error",
     r"{C}/depth_only.exr: no R, G, B or Y channel, and no layer with R, G and B", absent=["{O}/out.png"])

# ---- 8. scene values that failed late or vanished ---------------------------------------------------
write("overflow_number.json", '{"camera": {"position": [1e400, 0, 0]}}')
case(8, "number_1e400", render_scene("overflow_number.json"), "error",
     r"overflow_number.json: invalid JSON: number overflow parsing '1e400'")
scene("huge_camera.json", camera={"position": [1e30, 2, 4], "target": [0, 0, 0]})
case(8, "camera_position_1e30", render_scene("huge_camera.json"), "error",
     r"huge_camera.json: camera.position: 1e\+30 is too far from the origin")
scene("huge_light.json", lights=[{"type": "point", "position": [0, 1e35, 0]}])
case(8, "light_position_1e35", render_scene("huge_light.json"), "error",
     r"huge_light.json: lights\[0\].position: 1e\+35 is too far from the origin")
scene("huge_intensity.json", lights=[dict(LIGHT, intensity=1e30)])
case(8, "light_intensity_1e30", render_scene("huge_intensity.json"), "error",
     r"huge_intensity.json: lights\[0\].intensity: 1e\+30 is outside \[0, 1e\+09\]")
scene("huge_scale.json", models=[{"primitive": "cube", "scale": 1e30}])
case(8, "model_scale_1e30", render_scene("huge_scale.json"), "error", r"huge_scale.json: models\[0\].scale: 1e\+30")
write("big_18.obj", "v 0 0 0\nv 1e18 0 0\nv 0 1e18 0\nf 1 2 3\n")
write("placed_too_far.json", json.dumps({"models": [{"obj": "big_18.obj", "scale": 1e6}], "lights": [LIGHT]}))
case(8, "model_placed_beyond_1e18", render_scene("placed_too_far.json"), "error",
     r"placed_too_far.json: models\[0\]: placed up to 1e\+24 m from the origin, beyond the 1e\+18 m limit")
scene("far_3e38.json", camera=dict(CAMERA, far=3e38))
case(8, "far_3e38", render_scene("far_3e38.json"), "error", r"far_3e38.json: camera.far: 3e\+38 is beyond the 1e\+07 m maximum")
scene("near_tiny.json", camera=dict(CAMERA, near=1e-30, far=1e30))
case(8, "near_1e-30_far_1e30", render_scene("near_tiny.json"), "error", r"near_tiny.json: camera.near: 1e-30 is below")
scene("depth_ratio.json", camera=dict(CAMERA, near=1e-5, far=1e5))
case(8, "far_over_near_1e10", render_scene("depth_ratio.json"), "error", r"depth_ratio.json: camera.far: far / near is 1e\+10")
scene("description_number.json", description=42)
case(8, "description_not_string", render_scene("description_number.json"), "error",
     r"description_number.json: description: expected a string")
for r in ("1e6", "1e30"):
    scene(f"range_{r}.json", ambient=0, camera={"position": [1.2, 0.9, 1.6], "target": [0, 0, 0]}, lights=[{"type": "point", "position": [2, 2, 3], "intensity": 20, "range": float(r)}])
    case(8, f"point_light_range_{r}", render_scene(f"range_{r}.json", more=["--local-lights", "fullscreen"]), "ok",
         r"wrote ", outputs=["{O}/out.png"], covered=["{O}/out.png", 0.1])
scene("opacity_1_5.json", models=[{"primitive": "cube", "material": {"opacity": 1.5}}])
case(8, "material_opacity_1_5", render_scene("opacity_1_5.json"), "error",
     r"opacity_1_5.json: models\[0\].material.opacity: must be in \[0, 1\]")
case(8, "bench_vary_empty", ["bench", "--scene", "{C}/plain.json", "--vary", "", "--timings-json", "{O}/b.json"], "error",
     r"--vary '': empty", absent=["{O}/b.json"])
case(8, "bench_vary_blank", ["bench", "--scene", "{C}/plain.json", "--vary", "  ", "--timings-json", "{O}/b.json"], "error",
     r"--vary '  ': empty", absent=["{O}/b.json"])


# ---- 9. glTF: every element checked before use, errors name the file and the element -------------
# One triangle: 36 bytes of float positions, then 6 bytes of u16 indices 0 1 2 (as a data: URI).
TRI_B64 = base64.b64encode(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 2)).decode()


def gltf(name, buffers=None, views=None, accessors=None, primitive=None, **extra):
    body = {"asset": {"version": "2.0"},
            "buffers": buffers if buffers is not None else [{"byteLength": 42, "uri": "data:application/octet-stream;base64," + TRI_B64}],
            "bufferViews": views if views is not None else [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                                                            {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": accessors if accessors is not None else [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                                                                  {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
            "meshes": [{"primitives": [primitive or {"attributes": {"POSITION": 0}, "indices": 1}]}, ],
            "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
    body.update(extra)
    return write(name, json.dumps(body))


gltf("ok.gltf")
case(9, "gltf_ok", render_model("ok.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"], forbid=r"warning|error")
gltf("missing_buffer.gltf", buffers=[{"byteLength": 42, "uri": "nothere.bin"}])
case(9, "gltf_missing_buffer", render_model("missing_buffer.gltf"), "error", r"missing_buffer.gltf: buffers\[0\]\.uri: 'nothere.bin': file not found")
gltf("accessor_past_end.gltf", accessors=[{"bufferView": 0, "componentType": 5126, "count": 40, "type": "VEC3"}],
     primitive={"attributes": {"POSITION": 0}})
case(9, "gltf_accessor_out_of_range", render_model("accessor_past_end.gltf"), "error",
     r"accessor_past_end.gltf: meshes\[0\]\.primitives\[0\]\.attributes\.POSITION \(accessors\[0\]\): 40 elements from byte 0 run past the end of bufferViews\[0\]")
gltf("view_past_buffer.gltf", views=[{"buffer": 0, "byteOffset": 30, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}])
case(9, "gltf_view_out_of_range", render_model("view_past_buffer.gltf"), "error",
     r"view_past_buffer.gltf: bufferViews\[0\]: bytes 30\+36 run past the end of buffers\[0\] \(42 bytes\)")
gltf("bad_index.gltf", buffers=[{"byteLength": 42, "uri": "data:application/octet-stream;base64," +
                                 base64.b64encode(struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<3H", 0, 1, 900)).decode()}])
case(9, "gltf_bad_index", render_model("bad_index.gltf"), "error",
     r"bad_index.gltf: meshes\[0\]\.primitives\[0\]\.indices: index 900 at position 2 is beyond the 3 vertices")
gltf("required_extension.gltf", extensionsRequired=["KHR_texture_basisu"], extensionsUsed=["KHR_texture_basisu"])
case(9, "gltf_unknown_required_extension", render_model("required_extension.gltf"), "error",
     r"required_extension.gltf: extensionsRequired\[0\]: 'KHR_texture_basisu' is not supported")
# Compressed geometry whose stream is not one: 36 bytes of floats read as a Draco mesh, and a meshopt
# vertex stream cut to 4 bytes. One line naming the extension, never a crash.
gltf("draco_not_a_stream.gltf", extensionsUsed=["KHR_draco_mesh_compression"], extensionsRequired=["KHR_draco_mesh_compression"],
     primitive={"attributes": {"POSITION": 0}, "indices": 1,
                "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}})
case(9, "gltf_draco_not_a_stream", render_model("draco_not_a_stream.gltf"), "error",
     r"draco_not_a_stream.gltf: meshes\[0\]\.primitives\[0\]\.extensions\.KHR_draco_mesh_compression: Draco decoding failed: ")
gltf("meshopt_truncated.gltf", extensionsUsed=["EXT_meshopt_compression"], extensionsRequired=["EXT_meshopt_compression"],
     views=[{"buffer": 0, "byteOffset": 0, "byteLength": 36, "extensions": {"EXT_meshopt_compression": {
                 "buffer": 0, "byteOffset": 0, "byteLength": 4, "byteStride": 12, "count": 3, "mode": "ATTRIBUTES"}}},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6}])
case(9, "gltf_meshopt_truncated", render_model("meshopt_truncated.gltf"), "error",
     r"meshopt_truncated.gltf: bufferViews\[0\]\.extensions\.EXT_meshopt_compression: meshopt decoding failed \(ATTRIBUTES, 3 elements of 12 bytes from 4 bytes\)")
gltf("missing_texture.gltf", primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
     images=[{"uri": "missing.png"}], textures=[{"source": 0}], materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])
case(9, "gltf_missing_texture", render_model("missing_texture.gltf"), "fallback", r"missing.png.*using a checker texture",
     outputs=["{O}/out.png"])
gltf("blend.gltf", primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": 0}, materials=[{"name": "glass", "alphaMode": "BLEND"}])
case(9, "gltf_blend_drawn_blended", render_model("blend.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"],
     forbid=r"warning|error|MASK")
write("truncated.glb", b"glTF\x02\x00\x00\x00\xff\x00\x00\x00")
case(9, "glb_truncated", render_model("truncated.glb"), "error",
     r"truncated.glb: GLB header \(byte 8\): length 255, but the file has 12 bytes \(truncated\)")
# Properties of the wrong JSON type or outside their enumeration (tinygltf skipped them silently: the
# mesh, the emission or the blending were lost without a word); factors outside [0, 1]: clamped, warned.
gltf("wrong_type_mesh.gltf", nodes=[{"mesh": "0"}])
case(9, "gltf_wrong_type_index", render_model("wrong_type_mesh.gltf"), "error",
     r"wrong_type_mesh.gltf: nodes\[0\]\.mesh: expected an index \(an integer >= 0\), got a string \('0'\)")
gltf("wrong_type_factor.gltf", primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
     materials=[{"emissiveFactor": ["1", 0, 0]}])
case(9, "gltf_wrong_type_factor", render_model("wrong_type_factor.gltf"), "error",
     r"wrong_type_factor.gltf: materials\[0\]\.emissiveFactor\[0\]: expected a number, got a string \('1'\)")
gltf("wrong_enum.gltf", primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": 0}, materials=[{"alphaMode": "blend"}])
case(9, "gltf_wrong_enum", render_model("wrong_enum.gltf"), "error",
     r"wrong_enum.gltf: materials\[0\]\.alphaMode: expected one of OPAQUE, MASK, BLEND, got a string \('blend'\)")
gltf("gltf1.gltf", asset={"version": "1.0"}, scene="defaultScene")
case(9, "gltf_version_1", render_model("gltf1.gltf"), "error", r"gltf1.gltf: asset\.version: '1\.0' is not a glTF 2 version")
gltf("factor_out_of_range.gltf", primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
     materials=[{"pbrMetallicRoughness": {"roughnessFactor": 5}}])
case(9, "gltf_factor_clamped", render_model("factor_out_of_range.gltf"), "fallback",
     r"factor_out_of_range.gltf: materials\[0\]\.pbrMetallicRoughness\.roughnessFactor: 5 is outside \[0, 1\]; clamped",
     outputs=["{O}/out.png"])
gltf("scene_gltf_target.gltf")
scene("scene_bad_gltf.json", models=[{"gltf": "accessor_past_end.gltf"}])
case(9, "scene_gltf_error_names_both", render_scene("scene_bad_gltf.json"), "error",
     r"scene_bad_gltf.json: models\[0\]\.gltf: .*accessor_past_end.gltf: meshes\[0\]")

# ---- 10. structures that crashed, hung or took gigabytes (found by mutating the project's own files) -
# A node named twice as a child on each of 3 levels (at 40 levels: 2^40 walks), or a root listed twice.
gltf("node_twice.gltf", nodes=[{"children": [1, 1]}, {"children": [2, 2]}, {"mesh": 0}])
case(10, "gltf_node_reached_twice", render_model("node_twice.gltf"), "error",
     r"{C}/node_twice.gltf: nodes\[2\]: is reached twice \(from nodes\[1\]\.children\)", absent=["{O}/out.png"])
gltf("material_minus_2.gltf", primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": -2})
case(10, "gltf_material_below_minus_one", render_model("material_minus_2.gltf"), "error",
     r"{C}/material_minus_2.gltf: meshes\[0\]\.primitives\[0\]\.material: expected an index \(an integer >= 0\), got -2",
     absent=["{O}/out.png"])
gltf("image_view_past_buffer.gltf", views=[{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6},
                                           {"buffer": 0, "byteOffset": 30, "byteLength": 782}],
     primitive={"attributes": {"POSITION": 0}, "indices": 1, "material": 0},
     images=[{"mimeType": "image/png", "bufferView": 2}], textures=[{"source": 0}],
     materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])
case(10, "gltf_image_view_past_buffer", render_model("image_view_past_buffer.gltf"), "error",
     r"{C}/image_view_past_buffer.gltf: images\[0\]: bufferViews\[2\]: bytes 30\+782 run past the end of buffers\[0\] \(42 bytes\)",
     absent=["{O}/out.png"])
write("huge_polygon.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf " + " ".join(str(i % 3 + 1) for i in range(90000)) + "\n")
case(10, "obj_polygon_of_90000_corners", render_model("huge_polygon.obj"), "error",
     r"{C}/huge_polygon.obj:4: a face of 90000 corners", absent=["{O}/out.png"])
write("utf16.json", b"\xff\xfe" + '{"models": [{"primitive": "cube"}]}'.encode("utf-16-le"))
case(10, "scene_in_utf16", render_scene("utf16.json"), "error", r"{C}/utf16.json: is UTF-16 text", absent=["{O}/out.png"])
rle_line = b"\x02\x02\x00\x10" + b"".join(bytes((128 + 16, 100)) for _ in range(4))
write("rle_cut.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 16\n" + rle_line * 2 + rle_line[:7])
scene("env_rle_cut.json", environment={"map": "rle_cut.hdr"})
case(10, "hdr_run_length_cut", render_scene("env_rle_cut.json", more=[*ENV_SMALL]), "error",
     r"{C}/rle_cut.hdr: truncated: ", absent=["{O}/out.png"])
write("empty_size.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n")
scene("env_empty_size.json", environment={"map": "empty_size.hdr"})
case(10, "hdr_zero_by_zero", render_scene("env_empty_size.json", more=[*ENV_SMALL]), "error",
     r"{C}/empty_size.hdr: has no pixels \(0x0\)", absent=["{O}/out.png"])
write("gigabyte.tga", struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, 16384, 16384, 32, 0))
write("gigabyte_texture.obj", "mtllib gigabyte.mtl\nusemtl m\n" + CUBE_OBJ)
write("gigabyte.mtl", "newmtl m\nKd 1 1 1\nmap_Kd gigabyte.tga\n")
case(10, "texture_header_claims_a_gigabyte", render_model("gigabyte_texture.obj"), "fallback",
     r"warning: {C}/gigabyte.tga: claims 16384x16384 texels \(1024 MiB decoded\) from a 18-byte file.*using a checker texture",
     outputs=["{O}/out.png"])

# ---- 15. outputs: temporaries removed when a signal ends the process ----------------------------
# A sweep keeps its outputs as temporaries until the last value is rendered; the signal is sent as soon
# as the first one exists. SIGINT, SIGTERM and SIGHUP end the process (killed by that signal) with no
# file left; past the file-size limit (SIGXFSZ at its default: it used to kill the process and leave a
# 4 KB temporary) the write fails and the error names the file.
SWEEP = ["sweep", "--scene", "{C}/plain.json", "--knob", "shadow-size", "--size", "64x48", "--frames", "40", "--warmup", "1",
         "--out-dir", "{O}/sweep"]
for sig in ("INT", "TERM", "HUP"):
    case(15, f"sweep_sig{sig.lower()}_leaves_no_temporary", SWEEP, "signal", r"", signal=sig, timeout=120)
case(15, "full_disk_png_sigxfsz_default", render_scene("plain.json", out="{O}/big.png", more=["--size", "64x48"]), "error",
     r"{O}/big.png: cannot write: File too large", fsize_limit=100, sigxfsz="default", absent=["{O}/big.png"])

# ---- 11 to 19 (but 15): glTF (tests/bad_input/gltf_cases.py) ------------------------------------
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import gltf_cases  # noqa: E402
gltf_cases.add_cases(write, case, render_model, C)

with open(os.path.join(C, "manifest.json"), "w") as f:
    json.dump(cases, f, indent=1)
print(f"{len(cases)} cases in {C}")
