"""glTF cases of the bad-input corpus (make_corpus.py imports this): a small builder of valid glTF and
GLB files, the hand-made bad ones of each class, and mutations of valid files. Every case says what
must happen; run_corpus.py checks it."""
import base64, json, os, random, struct, zlib

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125
FORMATS = {FLOAT: "f", UBYTE: "B", USHORT: "H", UINT: "I"}


class Gltf:
    """A document and its one binary buffer, built view by view. as_gltf() embeds the buffer as a data
    URI; as_glb() writes it as the BIN chunk."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0"}, "bufferViews": [], "accessors": [], "meshes": [], "nodes": [],
                    "scenes": [{"nodes": []}], "scene": 0}
        self.bin = bytearray()

    def view(self, data):
        self.bin += b"\0" * (-len(self.bin) % 4)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, values, ctype, kind, count, view=True, **extra):
        acc = {"componentType": ctype, "count": count, "type": kind, **extra}
        if view:
            acc["bufferView"] = self.view(struct.pack(f"<{len(values)}{FORMATS[ctype]}", *values))
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def quad(self, normals=None, uvs=None, uv_type=FLOAT, tangents=None, material=None, **attributes):
        """A unit quad facing +Z (two triangles); each attribute list given replaces the default one
        (None: the default; False: no such attribute)."""
        a = {"POSITION": self.accessor([-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], FLOAT, "VEC3", 4,
                                       min=[-1, -1, 0], max=[1, 1, 0])}
        if normals is not False:
            a["NORMAL"] = self.accessor(normals or [0, 0, 1] * 4, FLOAT, "VEC3", 4)
        if uvs is not False:
            a["TEXCOORD_0"] = self.accessor(uvs or [0, 1, 1, 1, 1, 0, 0, 0], uv_type, "VEC2", 4)
        if tangents:
            a["TANGENT"] = self.accessor(tangents, FLOAT, "VEC4", 4)
        a.update(attributes)
        prim = {"attributes": a, "indices": self.accessor([0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6)}
        if material is not None:
            prim["material"] = material
        self.doc["meshes"].append({"primitives": [prim]})
        return len(self.doc["meshes"]) - 1

    def node(self, root=True, **fields):
        self.doc["nodes"].append(fields)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def camera(self, **perspective):
        p = {"yfov": 0.8, "znear": 0.1, **perspective}
        self.doc.setdefault("cameras", []).append({"type": "perspective", "perspective": p})
        # In front of the quad, looking down -Z at it.
        return self.node(camera=len(self.doc["cameras"]) - 1, translation=[0, 0, 3])

    def texture(self, image):
        self.doc.setdefault("images", []).append(image)
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        self.doc.setdefault("materials", []).append(
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": len(self.doc["textures"]) - 1}}})
        return len(self.doc["materials"]) - 1

    def document(self, embed=True):
        doc = json.loads(json.dumps(self.doc))
        if self.bin:
            buffer = {"byteLength": len(self.bin)}
            if embed:
                buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
            doc["buffers"] = [buffer]
        return doc

    def as_gltf(self):
        return json.dumps(self.document(), indent=1)

    def as_glb(self, doc=None, chunks=None, text=None):
        text = text if text is not None else json.dumps(doc if doc is not None else self.document(embed=False)).encode()
        text += b" " * (-len(text) % 4)
        body = struct.pack("<I4s", len(text), b"JSON") + text
        for kind, data in (chunks if chunks is not None else ([(b"BIN\0", bytes(self.bin) + b"\0" * (-len(self.bin) % 4))]
                                                               if self.bin else [])):
            body += struct.pack("<I4s", len(data), kind) + data
        return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def png(width, height, grey=128):
    """A greyscale 8-bit PNG of one value, compressed row by row (a big one stays small)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    z = zlib.compressobj(9)
    row = b"\0" + bytes([grey]) * width
    idat = b"".join(z.compress(row) for _ in range(height)) + z.flush()
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)) +
            chunk(b"IDAT", idat) + chunk(b"IEND", b""))


def lit_quad(**quad):
    """A quad with a camera and a light, as most cases here start."""
    g = Gltf()
    g.node(mesh=g.quad(**quad))
    g.camera()
    return g


def add_cases(write, case, render_model, C):
    graph = lambda name: ["graph", "--model", "{C}/" + name, "--gbuffer-mode", "classic"]

    # ---- 11. JSON: nesting, syntax, numbers; every error file:line:column -----------------------
    quad = lit_quad()
    ok_text = quad.as_gltf()
    deep = json.loads(ok_text)
    write("deep_extras.gltf", ok_text[:-1] + ', "extras": ' + "[" * 15000 + "]" * 15000 + "}")
    case(11, "json_extras_15000_deep", render_model("deep_extras.gltf"), "error",
         r"{C}/deep_extras.gltf:[0-9]+:[0-9]+: arrays and objects nested more than 128 levels deep", absent=["{O}/out.png"])
    write("deep_node.gltf", ok_text.replace('"nodes": [', '"nodes": [{"extras": ' + '{"a": ' * 100000 + "0" + "}" * 100000 + "}, ", 1))
    case(11, "json_node_100000_deep", render_model("deep_node.gltf"), "error",
         r"{C}/deep_node.gltf:[0-9]+:[0-9]+: arrays and objects nested more than 128 levels deep", absent=["{O}/out.png"])
    write("syntax.gltf", ok_text.replace('"2.0"', '"2.0",', 1))
    case(11, "json_trailing_comma", render_model("syntax.gltf"), "error",
         r"{C}/syntax.gltf:4:2: invalid JSON: syntax error while parsing object key - unexpected '}'; expected string literal")
    write("literal.gltf", ok_text.replace('"scene": 0', '"scene": tru', 1))
    case(11, "json_bad_literal", render_model("literal.gltf"), "error",
         r"{C}/literal.gltf:[0-9]+:[0-9]+: invalid JSON: syntax error while parsing value - invalid literal; last read: '[^']*'$")
    write("overflow.gltf", ok_text.replace('"yfov": 0.8', '"yfov": 1e309', 1))
    case(11, "json_number_1e309", render_model("overflow.gltf"), "error",
         r"{C}/overflow.gltf:[0-9]+:[0-9]+: number '1e309' is beyond the range of a double")
    write("cut.gltf", ok_text[:len(ok_text) // 2])
    case(11, "json_cut_in_half", render_model("cut.gltf"), "error", r"{C}/cut.gltf:[0-9]+:[0-9]+: invalid JSON: ")
    write("empty.gltf", "")
    case(11, "json_empty_file", render_model("empty.gltf"), "error",
         r"{C}/empty.gltf:1:1: invalid JSON: syntax error while parsing value - unexpected end of input")
    write("latin1.gltf", ok_text.replace('"2.0"', '"2.0", "generator": "caf\xe9"', 1).encode("latin-1"))
    case(11, "json_not_utf8", render_model("latin1.gltf"), "error",
         r"{C}/latin1.gltf:[0-9]+:[0-9]+: invalid JSON: .*ill-formed UTF-8 byte")
    glb_text = json.dumps(quad.document(embed=False)).replace('"scene": 0', '"scene": 0,,').encode()
    write("glb_syntax.glb", quad.as_glb(text=glb_text))
    case(11, "json_glb_chunk_syntax", render_model("glb_syntax.glb"), "error",
         r"{C}/glb_syntax.glb:1:[0-9]+: invalid JSON: syntax error while parsing object key")

    # ---- 12. values repaired, each kind with one warning naming the place and the count ---------
    nan = float("nan")
    # JSON has no NaN: the normals are written as bytes.
    g = lit_quad(normals=[0, 0, 1] * 4)
    nrm = g.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"]
    view = g.doc["bufferViews"][g.doc["accessors"][nrm]["bufferView"]]
    g.bin[view["byteOffset"]:view["byteOffset"] + 48] = struct.pack("<12f", nan, 0, 1, 0, 0, 0, 0, 0, 1, float("inf"), 0, 1)
    write("nan_normals.gltf", g.as_gltf())
    case(12, "gltf_nan_and_zero_normals", render_model("nan_normals.gltf"), "fallback",
         r"warning: {C}/nan_normals.gltf: meshes\[0\]\.primitives\[0\]\.attributes\.NORMAL \(accessors\[1\]\): 3 normals not finite "
         r"or zero-length; each replaced by the normal of its triangles", outputs=["{O}/out.png"], max_warnings=1)
    g = lit_quad()
    g.doc["accessors"][1].pop("bufferView")  # NORMAL without data: all zeros
    write("zero_normals.gltf", g.as_gltf())
    case(12, "gltf_normals_without_data", render_model("zero_normals.gltf"), "fallback",
         r"NORMAL \(accessors\[1\]\): 4 normals not finite or zero-length; each replaced", outputs=["{O}/out.png"], max_warnings=1)
    g = lit_quad()
    uv = g.doc["bufferViews"][g.doc["accessors"][2]["bufferView"]]
    g.bin[uv["byteOffset"]:uv["byteOffset"] + 8] = struct.pack("<2f", float("inf"), 0)
    write("inf_uv.gltf", g.as_gltf())
    case(12, "gltf_infinite_texcoord", render_model("inf_uv.gltf"), "fallback",
         r"TEXCOORD_0 \(accessors\[2\]\): 1 texture coordinates not finite; read as 0", outputs=["{O}/out.png"], max_warnings=1)
    write("nan_tangent.gltf", lit_quad(tangents=[1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 1]).as_gltf())
    case(12, "gltf_bad_tangents", render_model("nan_tangent.gltf"), "fallback",
         r"TANGENT \(accessors\[3\]\): 2 tangents not finite, zero-length or with w other than 1 or -1; the primitive's "
         r"tangents generated instead", outputs=["{O}/out.png"], max_warnings=1)
    write("ubyte_uv.gltf", lit_quad(uvs=[0, 255, 255, 255, 255, 0, 0, 0], uv_type=UBYTE).as_gltf())
    case(12, "gltf_ubyte_texcoord_not_normalized", render_model("ubyte_uv.gltf"), "fallback",
         r'TEXCOORD_0 \(accessors\[2\]\): integer texture coordinates without "normalized": true .*; read as normalized',
         outputs=["{O}/out.png"], max_warnings=1)
    write("ubyte_uv_normalized.gltf", lit_quad(uvs=[0, 255, 255, 255, 255, 0, 0, 0], uv_type=UBYTE).as_gltf().replace(
        '"type": "VEC2"', '"type": "VEC2", "normalized": true', 1))
    case(12, "gltf_ubyte_texcoord_normalized_ok", render_model("ubyte_uv_normalized.gltf"), "ok", r"wrote ",
         outputs=["{O}/out.png"], forbid=r"warning|error")
    for name, rotation, regex in (("zero", [0, 0, 0, 0], r"nodes\[0\]\.rotation: 1 rotations of length 0 \(not a rotation\); no rotation used"),
                                  ("denormal", [0, 1e-310, 0, 1e-310], r"nodes\[0\]\.rotation: 1 rotations not of unit length; normalized"),
                                  ("long", [0, 0, 0, 2], r"nodes\[0\]\.rotation: 1 rotations not of unit length; normalized")):
        g = Gltf()
        g.node(mesh=g.quad(), rotation=rotation)
        g.camera()
        write(f"rotation_{name}.gltf", g.as_gltf())
        case(12, f"gltf_rotation_{name}", render_model(f"rotation_{name}.gltf"), "fallback", regex, outputs=["{O}/out.png"],
             max_warnings=1)
    for name, perspective, regex in (
            ("yfov_4", {"yfov": 4}, r"cameras\[0\]\.perspective\.yfov: 4 rad is not below pi .*; 45 degrees used"),
            ("yfov_1e-9", {"yfov": 1e-9}, r"cameras\[0\]\.perspective\.yfov: 1e-09 rad .* is below the renderer's 0\.5 degrees; 0\.5 used"),
            ("zfar_below_znear", {"znear": 1, "zfar": 0.1}, r"cameras\[0\]\.perspective\.zfar: 0\.1 is not beyond znear 1; read as no zfar"),
            ("zfar_1e9_znear", {"znear": 0.001, "zfar": 1e9}, r"cameras\[0\]\.perspective\.zfar: 1e\+09 is more than 1e6 times znear")):
        g = Gltf()
        g.node(mesh=g.quad())
        g.camera(**perspective)
        write(f"camera_{name}.gltf", g.as_gltf())
        case(12, f"gltf_camera_{name}", render_model(f"camera_{name}.gltf"), "fallback", regex, outputs=["{O}/out.png"], max_warnings=1)
    # Twenty primitives with bad normals and ten nodes with zero rotations: one warning for each kind.
    g = Gltf()
    for i in range(20):
        mesh = g.quad(normals=[0, 0, 0] * 4)
        g.node(mesh=mesh, translation=[3 * (i % 5), 3 * (i // 5), 0], rotation=[0, 0, 0, 0] if i < 10 else [0, 0, 0, 1])
    write("many_repairs.gltf", g.as_gltf())
    case(12, "gltf_repairs_collapsed", render_model("many_repairs.gltf"), "fallback",
         r"nodes\[0\]\.rotation: 1 rotations of length 0 \(not a rotation\) \(and 9 more in 9 other nodes\); no rotation used.*"
         r"NORMAL \(accessors\[1\]\): 4 normals not finite or zero-length \(and 76 more in 19 other accessors\); each replaced",
         outputs=["{O}/out.png"], max_warnings=2)

    # ---- 13. text from the file in messages: quoted, cut with its length, control characters escaped
    escape_name = "\x1b[2J\x1b[H" + "X" * 10000
    g = lit_quad()
    g.doc["extensionsRequired"] = g.doc["extensionsUsed"] = [escape_name]
    write("long_extension.gltf", g.as_gltf())
    case(13, "gltf_extension_name_10000_with_escapes", render_model("long_extension.gltf"), "error",
         r"extensionsRequired\[0\]: '\\x1B\[2J\\x1B\[HX{33}\.\.\.' \(10007 characters\) is not supported",
         max_line=450)  # the name cut to 64 characters, then the list of the 9 supported extensions
    g = lit_quad()
    g.doc["asset"]["version"] = "\x1b]0;title\x07" + "9" * 5000
    write("long_version.gltf", g.as_gltf())
    case(13, "gltf_version_with_escapes", render_model("long_version.gltf"), "error",
         r"asset\.version: '\\x1B\]0;title\\x07[0-9]+\.\.\.' \(5010 characters\) is not a glTF 2 version", max_line=400)
    g = lit_quad()
    g.doc["materials"] = [{"alphaMode": "\x1b[31m" + "B" * 3000}]
    write("long_enum.gltf", g.as_gltf())
    case(13, "gltf_enum_value_3000_characters", render_model("long_enum.gltf"), "error",
         r"materials\[0\]\.alphaMode: expected one of OPAQUE, MASK, BLEND, got a string \('\\x1B\[31mB+\.\.\.' \(3005 characters\)\)",
         max_line=400)
    g = lit_quad()
    text = g.as_gltf()
    uri = text[text.index("data:application"):text.index('"', text.index("data:application"))]
    long_uri = uri.rstrip("=") + "A" * (70000 + -len(uri.rstrip("=")) % 4)
    bad_uri = uri[:60] + "%" + uri[61:].rstrip("=") + "A" * (70000 + -len(uri.rstrip("=")) % 4)
    write("bad_base64_buffer.gltf", text.replace(uri, bad_uri))
    case(13, "gltf_buffer_data_uri_70000_bad_base64", render_model("bad_base64_buffer.gltf"), "error",
         r"buffers\[0\]\.uri: data URI: character 24 of its base64 data, '%', is not base64$", max_line=400)
    write("long_buffer_uri.gltf", text.replace(uri, long_uri))
    case(13, "gltf_buffer_data_uri_too_long", render_model("long_buffer_uri.gltf"), "error",
         r"buffers\[0\]\.uri: the data URI holds [0-9]+ bytes, but byteLength is [0-9]+$", max_line=400)
    write("escape_buffer_name.gltf", text.replace(uri, "\\u001b[31mred%20file.bin"))
    case(13, "gltf_buffer_file_with_escapes", render_model("escape_buffer_name.gltf"), "error",
         r"buffers\[0\]\.uri: '\\x1B\[31mred%20file\.bin': '[^']*/\\x1B\[31mred file\.bin': file not found$", max_line=400)
    g = lit_quad(material=None)
    g.doc["meshes"][0]["primitives"][0]["material"] = g.texture({"uri": "\x1b[2J" + "t" * 5000 + ".png"})
    write("escape_image_name.gltf", g.as_gltf())
    case(13, "gltf_image_file_with_escapes", render_model("escape_image_name.gltf"), "fallback",
         r"warning: .*\\x1B\[2Jt+.*using a checker texture", outputs=["{O}/out.png"], max_line=700)

    # ---- 14. sparse accessors, read as the specification says -----------------------------------
    def sparse_quad(base=True, indices=(1, 2), values=(2, -1, 0, 2, 2, 0), index_type=UBYTE, count=None):
        """The quad, its POSITION sparse: corners `indices` moved to `values` (two of them by default:
        the quad becomes a bigger one), over the dense positions (`base`) or zeros."""
        g = Gltf()
        pos = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0] if base else [0] * 12
        sp = {"count": count or len(indices),
              "indices": {"bufferView": g.view(struct.pack(f"<{len(indices)}{FORMATS[index_type]}", *indices)),
                          "componentType": index_type},
              "values": {"bufferView": g.view(struct.pack(f"<{len(values)}f", *values))}}
        p = g.accessor(pos, FLOAT, "VEC3", 4, view=base, sparse=sp)
        g.doc["meshes"].append({"primitives": [{"attributes": {"POSITION": p},
                                                "indices": g.accessor([0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6)}]})
        g.node(mesh=0)
        g.camera()
        return g
    write("sparse_position.gltf", sparse_quad().as_gltf())
    case(14, "gltf_sparse_position", render_model("sparse_position.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"],
         forbid=r"warning|error", covered=["{O}/out.png", 0.1])
    write("sparse_position.glb", sparse_quad().as_glb())
    case(14, "glb_sparse_position", render_model("sparse_position.glb"), "ok", r"wrote ", outputs=["{O}/out.png"],
         forbid=r"warning|error")
    write("sparse_no_view.gltf", sparse_quad(base=False, indices=(0, 1, 2, 3), values=(-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0)).as_gltf())
    case(14, "gltf_sparse_position_over_zeros", render_model("sparse_no_view.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"],
         forbid=r"warning|error", covered=["{O}/out.png", 0.05])
    write("sparse_index_past.gltf", sparse_quad(indices=(1, 9)).as_gltf())
    case(14, "gltf_sparse_index_past_count", render_model("sparse_index_past.gltf"), "error",
         r"attributes\.POSITION \(accessors\[0\]\)\.sparse\.indices: index 9 at position 1 is beyond the accessor's 4 elements")
    write("sparse_unordered.gltf", sparse_quad(indices=(2, 1)).as_gltf())
    case(14, "gltf_sparse_indices_not_increasing", render_model("sparse_unordered.gltf"), "error",
         r"sparse\.indices: index 1 at position 1 does not follow 2 \(sparse indices are strictly increasing\)")
    write("sparse_values_short.gltf", sparse_quad(values=(2, -1, 0)).as_gltf())
    case(14, "gltf_sparse_values_past_view", render_model("sparse_values_short.gltf"), "error",
         r"sparse\.values: 2 elements of 12 bytes from byte 0 run past the end of bufferViews\[1\] \(12 bytes\)")
    write("sparse_count_over.gltf", sparse_quad(count=5).as_gltf())
    case(14, "gltf_sparse_count_over_accessor", render_model("sparse_count_over.gltf"), "error",
         r"accessors\[0\]\.sparse\.count: 5 is more than the accessor's count 4")
    g = sparse_quad()
    del g.doc["accessors"][0]["sparse"]["values"]
    write("sparse_no_values.gltf", g.as_gltf())
    case(14, "gltf_sparse_without_values", render_model("sparse_no_values.gltf"), "error",
         r"accessors\[0\]\.sparse\.values: missing \(the glTF schema requires it\)")

    # ---- 16. images: size checked from the header, bad data falls back to the checker --------------
    g = lit_quad(material=None)
    g.doc["meshes"][0]["primitives"][0]["material"] = g.texture({"mimeType": "image/png", "bufferView": g.view(png(8193, 8193))})
    write("huge_texture.glb", g.as_glb())
    case(16, "glb_texture_8193_squared", render_model("huge_texture.glb"), "fallback",
         r"warning: {C}/huge_texture.glb#images\[0\]: 8193x8193 texels \(256\.1 MiB decoded\) are more than one texture may take "
         r"\(256 MiB: 8192x8192\); refused before decoding; using a checker texture", outputs=["{O}/out.png"], timeout=20,
         max_warnings=1)
    for name, uri, regex in (
            ("bad_base64", "data:image/png;base64," + base64.b64encode(png(4, 4)).decode()[:20] + "!!" + "A" * 2,
             r"#images\[0\]: data URI: character 21 of its base64 data, '!', is not base64; using a checker texture"),
            ("not_base64", "data:image/png,%89PNG", r"#images\[0\]: data URI: not base64-encoded .*; using a checker texture"),
            ("empty_data", "data:image/png;base64,", r"#images\[0\]: data URI: no data; using a checker texture"),
            ("webp", "data:image/webp;base64,UklGRhYAAABXRUJQ", r"#images\[0\]: unreadable image.*; using a checker texture")):
        g = lit_quad(material=None)
        g.doc["meshes"][0]["primitives"][0]["material"] = g.texture({"uri": uri})
        write(f"image_{name}.gltf", g.as_gltf())
        case(16, f"gltf_image_data_uri_{name}", render_model(f"image_{name}.gltf"), "fallback", r"warning: {C}/image_" + name + r"\.gltf" + regex,
             outputs=["{O}/out.png"], max_warnings=1)
    g = lit_quad(material=None)
    g.doc["meshes"][0]["primitives"][0]["material"] = g.texture({"uri": "data:image/png;base64," + base64.b64encode(png(4, 4)).decode()})
    write("image_data_uri_ok.gltf", g.as_gltf())
    case(16, "gltf_image_data_uri_ok", render_model("image_data_uri_ok.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"],
         forbid=r"warning|error")

    # ---- 17. GLB: errors name the chunk, its offset and the lengths ----------------------------------
    good = lit_quad().as_glb()
    json_length = struct.unpack_from("<I", good, 12)[0]
    bin_at = 20 + json_length
    write("glb_ok.glb", good)
    case(17, "glb_ok", render_model("glb_ok.glb"), "ok", r"wrote ", outputs=["{O}/out.png"], forbid=r"warning|error")
    write("glb_10_bytes.glb", good[:10])
    case(17, "glb_shorter_than_header", render_model("glb_10_bytes.glb"), "error",
         r"glb_10_bytes.glb: GLB header: the file has 10 bytes, the header needs 12$")
    write("glb_cut.glb", good[:len(good) - 40])
    case(17, "glb_cut_short", render_model("glb_cut.glb"), "error",
         rf"glb_cut.glb: GLB header \(byte 8\): length {len(good)}, but the file has {len(good) - 40} bytes \(truncated\)$")
    def patched(data, at, value):
        return data[:at] + struct.pack("<I", value) + data[at + 4:]
    write("glb_json_long.glb", patched(good, 12, len(good)))
    case(17, "glb_json_chunk_past_end", render_model("glb_json_long.glb"), "error",
         rf"glb_json_long.glb: chunk 0 \(JSON\) at byte 12: length {len(good)}, but {len(good) - 20} bytes follow its header "
         rf"\(the GLB is {len(good)} bytes\)$")
    write("glb_bin_long.glb", patched(good, bin_at, 4096))
    case(17, "glb_bin_chunk_past_end", render_model("glb_bin_long.glb"), "error",
         rf"glb_bin_long.glb: chunk 1 \(BIN\) at byte {bin_at}: length 4096, but {len(good) - bin_at - 8} bytes follow its header")
    write("glb_bin_first.glb", patched(good, 16, 0x004E4942))
    case(17, "glb_first_chunk_not_json", render_model("glb_bin_first.glb"), "error",
         r"glb_bin_first.glb: chunk 0 \(BIN\) at byte 12: type 'BIN\\x00' \(0x004E4942\), but the first chunk must be JSON 'JSON' \(0x4E4F534A\)$")
    write("glb_bin_odd.glb", patched(good, bin_at, struct.unpack_from("<I", good, bin_at)[0] - 1))
    case(17, "glb_bin_not_padded", render_model("glb_bin_odd.glb"), "error",
         rf"glb_bin_odd.glb: chunk 1 \(BIN\) at byte {bin_at}: length [0-9]+ is not a multiple of 4")
    write("glb_version_1.glb", patched(good, 4, 1))
    case(17, "glb_version_1", render_model("glb_version_1.glb"), "error", r"glb_version_1.glb: GLB container version 1: lightpass reads glTF 2\.0")
    write("glb_not_glb.glb", b"GLTF" + good[4:])
    case(17, "glb_without_magic", render_model("glb_not_glb.glb"), "error",
         r"glb_not_glb.glb: not a GLB file: it starts with 'GLTF', not the magic 'glTF'")
    write("glb_trailing.glb", good + b"\0" * 16)
    case(17, "glb_bytes_after_length", render_model("glb_trailing.glb"), "fallback",
         rf"warning: {{C}}/glb_trailing.glb: 16 bytes after the GLB's length \({len(good)} bytes, header byte 8\) are ignored",
         outputs=["{O}/out.png"], max_warnings=1)
    # A chunk of a type no reader knows, between JSON and BIN or instead of BIN: ignored, as the spec says.
    embedded = lit_quad()
    write("glb_unknown_chunk.glb", embedded.as_glb(doc=embedded.document(embed=True), chunks=[(b"XTRA", b"1234")]))
    case(17, "glb_unknown_chunk_ignored", render_model("glb_unknown_chunk.glb"), "ok", r"wrote ", outputs=["{O}/out.png"],
         forbid=r"warning|error")
    g = lit_quad()
    doc = g.document(embed=False)
    doc["buffers"][0]["byteLength"] += 64
    write("glb_buffer_past_bin.glb", g.as_glb(doc=doc))
    case(17, "glb_buffer_longer_than_bin", render_model("glb_buffer_past_bin.glb"), "error",
         rf"glb_buffer_past_bin.glb: buffers\[0\]\.byteLength: [0-9]+ bytes, but the GLB's BIN chunk \(chunk 1 at byte {bin_at}\) holds [0-9]+$")
    write("glb_no_bin.glb", g.as_glb(chunks=[]))
    case(17, "glb_buffer_without_bin", render_model("glb_no_bin.glb"), "error",
         r"glb_no_bin.glb: buffers\[0\]: has no uri, and the GLB has no BIN chunk to hold its data$")

    # ---- 18. deep and wide structure: no recursion a file can overflow --------------------------------
    def chain(levels):
        g = Gltf()
        mesh = g.quad()
        g.node(children=[1])
        for i in range(1, levels):
            g.node(root=False, **({"children": [i + 1]} if i + 1 < levels else {"mesh": mesh}), translation=[0, 0, 0.0])
        return g
    write("chain_1023.gltf", chain(1023).as_gltf())
    # Under a 1 MiB stack (ulimit -s 1024): the node tree is walked with a stack of its own.
    case(18, "gltf_node_chain_1023_under_1mib_stack", graph("chain_1023.gltf"), "ok", r"frame graph for", stack_kib=1024,
         forbid=r"warning|error")
    write("chain_1025.gltf", chain(1025).as_gltf())
    case(18, "gltf_node_chain_1025", graph("chain_1025.gltf"), "error",
         r"{C}/chain_1025.gltf: nodes\[1024\]: is more than 1024 levels deep in the node hierarchy", stack_kib=1024)
    write("extras_1000_deep.gltf", ok_text[:-1] + ', "extras": ' + "[" * 1000 + "]" * 1000 + "}")
    case(18, "gltf_extras_1000_deep_under_1mib_stack", graph("extras_1000_deep.gltf"), "error",
         r"{C}/extras_1000_deep.gltf:[0-9]+:[0-9]+: arrays and objects nested more than 128 levels deep", stack_kib=1024)
    write("extras_120_deep.gltf", ok_text[:-1] + ', "extras": ' + "[" * 120 + "]" * 120 + "}")
    case(18, "gltf_extras_120_deep_under_1mib_stack", graph("extras_120_deep.gltf"), "ok", r"frame graph for", stack_kib=1024,
         forbid=r"warning|error")

    # ---- 19. mutations of valid files: whatever each becomes, it loads or fails with one clean line ---
    rng = random.Random(41)
    full = Gltf()
    material = full.texture({"uri": "data:image/png;base64," + base64.b64encode(png(4, 4)).decode()})
    full.node(mesh=full.quad(tangents=[1, 0, 0, 1] * 4, material=material), rotation=[0, 0.38268343, 0, 0.92387953],
              children=[1])
    full.node(root=False, mesh=0, translation=[2, 0, 0], scale=[0.5, 0.5, 0.5])
    full.camera()
    full.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    full.doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 5, "spot": {"outerConeAngle": 0.6}}]}}
    full.node(translation=[0, 2, 2], extensions={"KHR_lights_punctual": {"light": 0}})
    glb = Gltf()
    glb_material = glb.texture({"mimeType": "image/png", "bufferView": glb.view(png(4, 4))})
    glb.node(mesh=glb.quad(material=glb_material))
    glb.camera()
    originals = {"m.gltf": full.as_gltf().encode(), "m.glb": glb.as_glb()}
    values = [None, -1, 0, 1, 0.5, 3e38, 1e300, -1e300, 2 ** 31, 2 ** 63, "", "x" * 300, "\x1b[2J", [], {}, [0] * 17, True]

    def paths(node, at=()):
        yield at
        if isinstance(node, dict):
            for k, v in node.items():
                yield from paths(v, at + (k,))
        elif isinstance(node, list):
            for i, v in enumerate(node[:6]):
                yield from paths(v, at + (i,))

    def mutated(doc, at, value, delete):
        doc = json.loads(json.dumps(doc))
        parent = doc
        for key in at[:-1]:
            parent = parent[key]
        if delete:
            del parent[at[-1]]
        else:
            parent[at[-1]] = value
        return doc

    count = 0
    for original, data in originals.items():
        stem = original.replace(".", "_")
        if original.endswith(".gltf"):
            doc = json.loads(data)
        else:
            n = struct.unpack_from("<I", data, 12)[0]
            doc = json.loads(data[20:20 + n])
        every = [p for p in paths(doc) if p]
        # 80 elements of each file (of about 150 and 60), each deleted or given a value of another kind,
        # picked at random (seeded: the same cases every run).
        for at in sorted(rng.sample(every, min(len(every), 80)), key=every.index):
            choice = rng.randrange(len(values) + 1)
            changed = mutated(doc, at, values[choice - 1] if choice else None, choice == 0)
            text = json.dumps(changed)
            if len(text) > 4_000_000:
                continue
            body = text.encode() if original.endswith(".gltf") else glb.as_glb(text=text.encode())
            name = f"mutant_{stem}_{count:04d}{os.path.splitext(original)[1]}"
            write(name, body)
            case(19, name, graph(name), "any", r"{C}/" + name.replace(".", r"\."), max_line=400, timeout=20)
            count += 1
        # Bytes: the file cut at 16 places, and 24 single bytes changed.
        for k in range(16):
            name = f"mutant_{stem}_cut{k:02d}{os.path.splitext(original)[1]}"
            write(name, data[:len(data) * k // 16])
            case(19, name, graph(name), "any", r"{C}/" + name.replace(".", r"\."), max_line=400, timeout=20)
        for k in range(24):
            at = rng.randrange(len(data))
            name = f"mutant_{stem}_byte{k:02d}{os.path.splitext(original)[1]}"
            write(name, data[:at] + bytes([rng.randrange(256)]) + data[at + 1:])
            case(19, name, graph(name), "any", r"{C}/" + name.replace(".", r"\."), max_line=400, timeout=20)

    # ---- 20. animations: a bad channel or sampler is one line naming the file and the element --------
    def animated(times=(0, 1), values=(0, 0, 0, 1, 0, 0), path="translation", interpolation="LINEAR", kind="VEC3", node=0):
        g = lit_quad()
        inp = g.accessor(list(times), FLOAT, "SCALAR", len(times))
        out = g.accessor(list(values), FLOAT, kind, len(values) // (4 if kind == "VEC4" else 3))
        g.doc["animations"] = [{"name": "a", "channels": [{"sampler": 0, "target": {"node": node, "path": path}}],
                                "samplers": [{"input": inp, "output": out, "interpolation": interpolation}]}]
        return g
    write("anim_ok.gltf", animated().as_gltf())
    case(20, "gltf_animation_ok", render_model("anim_ok.gltf") + ["--time", "0.5", "--fps", "30"], "ok", r"animation pose: CPU median",
         outputs=["{O}/out.png"])
    write("anim_node.gltf", animated(node=9).as_gltf())
    case(20, "gltf_animation_node_out_of_range", render_model("anim_node.gltf"), "error",
         r"{C}/anim_node\.gltf: animations\[0\]\.channels\[0\]\.target\.node: 9 does not exist \([0-9]+ nodes\)$", absent=["{O}/out.png"])
    write("anim_counts.gltf", animated(values=(0, 0, 0, 1, 0, 0, 2, 0, 0)).as_gltf())
    case(20, "gltf_animation_counts_mismatch", render_model("anim_counts.gltf"), "error",
         r"{C}/anim_counts\.gltf: animations\[0\]\.samplers\[0\]\.output \(accessors\[5\]\): 3 values for 2 key times: LINEAR needs 2 \(one a key\)$")
    write("anim_cubic_counts.gltf", animated(interpolation="CUBICSPLINE").as_gltf())
    case(20, "gltf_animation_cubic_counts", render_model("anim_cubic_counts.gltf"), "error",
         r"{C}/anim_cubic_counts\.gltf: animations\[0\]\.samplers\[0\]\.output \(accessors\[5\]\): 2 values for 2 key times: CUBICSPLINE needs 6")
    write("anim_times.gltf", animated(times=(0, 2, 1), values=(0, 0, 0, 1, 0, 0, 2, 0, 0)).as_gltf())
    case(20, "gltf_animation_times_not_increasing", render_model("anim_times.gltf"), "error",
         r"{C}/anim_times\.gltf: animations\[0\]\.samplers\[0\]\.input \(accessors\[4\]\): key time 2 \(1\) is not after key time 1 \(2\): key times must increase$")
    write("anim_nan_time.gltf", animated(times=(0, float("nan"))).as_gltf())
    case(20, "gltf_animation_nan_time", render_model("anim_nan_time.gltf"), "error",
         r"{C}/anim_nan_time\.gltf: animations\[0\]\.samplers\[0\]\.input \(accessors\[4\]\): key time 1 is not finite$")
    write("anim_inf_value.gltf", animated(values=(0, 0, 0, float("inf"), 0, 0)).as_gltf())
    case(20, "gltf_animation_inf_value", render_model("anim_inf_value.gltf"), "error",
         r"{C}/anim_inf_value\.gltf: animations\[0\]\.samplers\[0\]\.output \(accessors\[5\]\): value 1 is not finite$")
    zero_rotation = animated(values=(0, 0, 0, 1, 0, 0, 0, 0), path="rotation", kind="VEC4")
    write("anim_zero_rotation.gltf", zero_rotation.as_gltf())
    case(20, "gltf_animation_zero_rotation", render_model("anim_zero_rotation.gltf"), "error",
         r"{C}/anim_zero_rotation\.gltf: animations\[0\]\.samplers\[0\]\.output \(accessors\[5\]\): value 1 is a rotation of length 0$")
    on_matrix = animated()
    on_matrix.doc["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    write("anim_matrix.gltf", on_matrix.as_gltf())
    case(20, "gltf_animation_on_matrix_node", render_model("anim_matrix.gltf"), "error",
         r"{C}/anim_matrix\.gltf: animations\[0\]\.channels\[0\]\.target\.node: nodes\[0\] has a matrix; an animated node must have translation, rotation and scale instead$")
    # The animated file mutated as class 19 mutates: it loads or fails with one clean line.
    anim_doc = json.loads(animated().as_gltf())
    anim_paths = [p for p in paths(anim_doc) if p and p[0] in ("animations", "accessors")]
    for k, at in enumerate(sorted(rng.sample(anim_paths, min(len(anim_paths), 30)), key=anim_paths.index)):
        choice = rng.randrange(len(values) + 1)
        name = f"mutant_anim_{k:02d}.gltf"
        write(name, json.dumps(mutated(anim_doc, at, values[choice - 1] if choice else None, choice == 0)))
        case(20, name, graph(name), "any", r"{C}/" + name.replace(".", r"\."), max_line=400, timeout=20)

    # ---- 21. skins and morph targets: a bad joint, weight, bind matrix or target is one line -------
    def skinned(joints=(0, 0, 0, 0) * 4, weights=(1, 0, 0, 0) * 4, weight_count=4, ibm=None):
        """The lit quad skinned to one joint (node 2, a root); accessors 4 JOINTS_0, 5 WEIGHTS_0, 6 the
        inverse bind matrices when given."""
        g = lit_quad()
        attributes = g.doc["meshes"][0]["primitives"][0]["attributes"]
        attributes["JOINTS_0"] = g.accessor(list(joints), UBYTE, "VEC4", 4)
        attributes["WEIGHTS_0"] = g.accessor(list(weights)[:4 * weight_count], FLOAT, "VEC4", weight_count)
        skin = {"joints": [g.node(translation=[0, 0, 0])]}
        if ibm is not None:
            skin["inverseBindMatrices"] = g.accessor(list(ibm), FLOAT, "MAT4", len(ibm) // 16)
        g.doc["nodes"][0]["skin"] = 0
        g.doc["skins"] = [skin]
        return g
    identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    write("skin_ok.gltf", skinned(ibm=identity).as_gltf())
    case(21, "gltf_skin_ok", render_model("skin_ok.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"], forbid=r"warning|error")
    write("skin_joint_range.gltf", skinned(joints=(0, 0, 0, 0) * 3 + (3, 0, 0, 0)).as_gltf())
    case(21, "gltf_skin_joint_out_of_range", render_model("skin_joint_range.gltf"), "error",
         r"{C}/skin_joint_range\.gltf: meshes\[0\]\.primitives\[0\]\.attributes\.JOINTS_0 \(accessors\[4\]\): joint 3 of vertex 3 is beyond skins\[0\]'s 1 joints$",
         absent=["{O}/out.png"])
    write("skin_weight_count.gltf", skinned(weight_count=3).as_gltf())
    case(21, "gltf_skin_weights_count_mismatch", render_model("skin_weight_count.gltf"), "error",
         r"{C}/skin_weight_count\.gltf: meshes\[0\]\.primitives\[0\]\.attributes\.WEIGHTS_0: 3 elements, but POSITION has 4$")
    write("skin_nan_ibm.gltf", skinned(ibm=identity[:12] + [float("nan")] + identity[13:]).as_gltf())
    case(21, "gltf_skin_nan_inverse_bind", render_model("skin_nan_ibm.gltf"), "error",
         r"{C}/skin_nan_ibm\.gltf: skins\[0\]\.inverseBindMatrices \(accessors\[6\]\): matrix 0 \(for joint 0\) is not finite$")
    write("skin_weights_sum.gltf", skinned(weights=(2, 0, 0, 0) * 4).as_gltf())
    case(21, "gltf_skin_weights_normalised", render_model("skin_weights_sum.gltf"), "fallback",
         r"warning: {C}/skin_weights_sum\.gltf: meshes\[0\]\.primitives\[0\]\.attributes\.WEIGHTS_0 \(accessors\[5\]\): 4 vertices whose "
         r"joint weights do not sum to 1; normalized", outputs=["{O}/out.png"], max_warnings=1)
    # Ten skinned primitives with unnormalised weights: one line with the count.
    g = skinned(weights=(2, 0, 0, 0) * 4)
    for _ in range(9):
        g.doc["meshes"][0]["primitives"].append(json.loads(json.dumps(g.doc["meshes"][0]["primitives"][0])))
    for k in range(1, 10):
        attributes = g.doc["meshes"][0]["primitives"][k]["attributes"]
        attributes["WEIGHTS_0"] = g.accessor([3, 0, 0, 0] * 4, FLOAT, "VEC4", 4)
    write("skin_weights_many.gltf", g.as_gltf())
    case(21, "gltf_skin_weights_collapsed", render_model("skin_weights_many.gltf"), "fallback",
         r"WEIGHTS_0 \(accessors\[5\]\): 4 vertices whose joint weights do not sum to 1 \(and 36 more in 9 other accessors\); normalized",
         outputs=["{O}/out.png"], max_warnings=1)
    def morphed(target_count=4, mesh_weights=(0.5,)):
        g = lit_quad()
        g.doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": g.accessor([0, 0, 1] * target_count, FLOAT, "VEC3", target_count)}]
        g.doc["meshes"][0]["weights"] = list(mesh_weights)
        return g
    write("morph_ok.gltf", morphed().as_gltf())
    case(21, "gltf_morph_ok", render_model("morph_ok.gltf"), "ok", r"wrote ", outputs=["{O}/out.png"], forbid=r"warning|error")
    write("morph_count.gltf", morphed(target_count=3).as_gltf())
    case(21, "gltf_morph_target_count_mismatch", render_model("morph_count.gltf"), "error",
         r"{C}/morph_count\.gltf: meshes\[0\]\.primitives\[0\]\.targets\[0\]\.POSITION: 3 elements, but POSITION has 4$")
    write("morph_weights.gltf", morphed(mesh_weights=(0.5, 0.5)).as_gltf())
    case(21, "gltf_morph_weights_mismatch", render_model("morph_weights.gltf"), "error",
         r"{C}/morph_weights\.gltf: meshes\[0\]\.weights: 2 weights for 1 morph targets \(one a target\)$")

    # ---- 22. material extensions: a value outside the schema is one line naming the field ----------
    for name, spec, regex in [
            ("specular_factor", {"specularFactor": 1.5},
             r"materials\[0\]\.extensions\.KHR_materials_specular\.specularFactor: 1\.5 must be in \[0, 1\]$"),
            ("specular_colour", {"specularColorFactor": [1, -0.25, 1]},
             r"materials\[0\]\.extensions\.KHR_materials_specular\.specularColorFactor\[1\]: -0\.25 must be >= 0$"),
            ("specular_colour_length", {"specularColorFactor": [1, 1]},
             r"materials\[0\]\.extensions\.KHR_materials_specular\.specularColorFactor: expected an array of 3 numbers, got an array of 2$"),
            ("specular_factor_string", {"specularFactor": "high"},
             r"materials\[0\]\.extensions\.KHR_materials_specular\.specularFactor: expected a number, got a string"),
    ]:
        g = lit_quad(material=0)
        g.doc["materials"] = [{"extensions": {"KHR_materials_specular": spec}}]
        g.doc["extensionsUsed"] = ["KHR_materials_specular"]
        write(f"{name}.gltf", g.as_gltf())
        case(22, f"gltf_{name}", render_model(f"{name}.gltf"), "error", r"{C}/" + name + r"\.gltf: " + regex,
             absent=["{O}/out.png"])
    # KHR_materials_clearcoat: factors outside [0, 1] (a negative one, one above), a string, and a
    # textureInfo without its index (1e999, JSON's only way to write a non-finite number, fails the parse).
    for name, coat, regex in [
            ("clearcoat_factor", {"clearcoatFactor": 1.5},
             r"materials\[0\]\.extensions\.KHR_materials_clearcoat\.clearcoatFactor: 1\.5 must be in \[0, 1\]$"),
            ("clearcoat_roughness_negative", {"clearcoatFactor": 1, "clearcoatRoughnessFactor": -0.25},
             r"materials\[0\]\.extensions\.KHR_materials_clearcoat\.clearcoatRoughnessFactor: -0\.25 must be in \[0, 1\]$"),
            ("clearcoat_factor_string", {"clearcoatFactor": "glossy"},
             r"materials\[0\]\.extensions\.KHR_materials_clearcoat\.clearcoatFactor: expected a number, got a string"),
            ("clearcoat_texture_no_index", {"clearcoatFactor": 1, "clearcoatTexture": {"texCoord": 0}},
             r"materials\[0\]\.extensions\.KHR_materials_clearcoat\.clearcoatTexture\.index: missing \(the glTF schema requires it\)$"),
    ]:
        g = lit_quad(material=0)
        g.doc["materials"] = [{"extensions": {"KHR_materials_clearcoat": coat}}]
        g.doc["extensionsUsed"] = ["KHR_materials_clearcoat"]
        write(f"{name}.gltf", g.as_gltf())
        case(22, f"gltf_{name}", render_model(f"{name}.gltf"), "error", r"{C}/" + name + r"\.gltf: " + regex,
             absent=["{O}/out.png"])
    # KHR_materials_transmission and KHR_materials_volume: a factor outside [0, 1], a negative thickness,
    # an attenuation distance of 0, an attenuation colour above 1 or of the wrong length, a string.
    for name, ext, regex in [
            ("transmission_factor", {"KHR_materials_transmission": {"transmissionFactor": 1.25}},
             r"materials\[0\]\.extensions\.KHR_materials_transmission\.transmissionFactor: 1\.25 must be in \[0, 1\]$"),
            ("transmission_factor_string", {"KHR_materials_transmission": {"transmissionFactor": "clear"}},
             r"materials\[0\]\.extensions\.KHR_materials_transmission\.transmissionFactor: expected a number, got a string"),
            ("transmission_texture_no_index", {"KHR_materials_transmission": {"transmissionFactor": 1, "transmissionTexture": {"texCoord": 0}}},
             r"materials\[0\]\.extensions\.KHR_materials_transmission\.transmissionTexture\.index: missing \(the glTF schema requires it\)$"),
            ("volume_thickness_negative", {"KHR_materials_transmission": {"transmissionFactor": 1},
                                           "KHR_materials_volume": {"thicknessFactor": -0.5}},
             r"materials\[0\]\.extensions\.KHR_materials_volume\.thicknessFactor: -0\.5 must be >= 0$"),
            ("volume_attenuation_distance_zero", {"KHR_materials_transmission": {"transmissionFactor": 1},
                                                  "KHR_materials_volume": {"attenuationDistance": 0}},
             r"materials\[0\]\.extensions\.KHR_materials_volume\.attenuationDistance: 0 must be > 0 \(leave it out for no absorption\)$"),
            ("volume_attenuation_colour", {"KHR_materials_transmission": {"transmissionFactor": 1},
                                           "KHR_materials_volume": {"attenuationColor": [1, 1.5, 1]}},
             r"materials\[0\]\.extensions\.KHR_materials_volume\.attenuationColor\[1\]: 1\.5 must be in \[0, 1\]$"),
            ("volume_attenuation_colour_length", {"KHR_materials_transmission": {"transmissionFactor": 1},
                                                  "KHR_materials_volume": {"attenuationColor": [1, 1]}},
             r"materials\[0\]\.extensions\.KHR_materials_volume\.attenuationColor: expected an array of 3 numbers, got an array of 2$"),
    ]:
        g = lit_quad(material=0)
        g.doc["materials"] = [{"extensions": ext}]
        g.doc["extensionsUsed"] = sorted(ext)
        write(f"{name}.gltf", g.as_gltf())
        case(22, f"gltf_{name}", render_model(f"{name}.gltf"), "error", r"{C}/" + name + r"\.gltf: " + regex,
             absent=["{O}/out.png"])
    # KHR_materials_variants: a mapping to a material or a variant that is not there, a variant mapped
    # twice in one primitive, a variant name that is not a string.
    for name, mappings, variants, regex in [
            ("variants_material", [{"material": 7, "variants": [0]}], [{"name": "a"}],
             r"meshes\[0\]\.primitives\[0\]\.extensions\.KHR_materials_variants\.mappings\[0\]\.material: material 7 does not exist \(1 materials\)$"),
            ("variants_index", [{"material": 0, "variants": [2]}], [{"name": "a"}],
             r"meshes\[0\]\.primitives\[0\]\.extensions\.KHR_materials_variants\.mappings\[0\]\.variants\[0\]: variant 2 does not exist \(1 variants\)$"),
            ("variants_twice", [{"material": 0, "variants": [0]}, {"material": 0, "variants": [0]}], [{"name": "a"}],
             r"meshes\[0\]\.primitives\[0\]\.extensions\.KHR_materials_variants\.mappings\[1\]\.variants\[0\]: variant 0 is mapped twice in this primitive$"),
            ("variants_name", [{"material": 0, "variants": [0]}], [{"name": 5}],
             r"extensions\.KHR_materials_variants\.variants\[0\]\.name: expected a string, got 5$"),
    ]:
        g = lit_quad(material=0)
        g.doc["materials"] = [{}]
        g.doc["extensionsUsed"] = ["KHR_materials_variants"]
        g.doc["extensions"] = {"KHR_materials_variants": {"variants": variants}}
        g.doc["meshes"][0]["primitives"][0]["extensions"] = {"KHR_materials_variants": {"mappings": mappings}}
        write(f"{name}.gltf", g.as_gltf())
        case(22, f"gltf_{name}", render_model(f"{name}.gltf"), "error", r"{C}/" + name + r"\.gltf: " + regex,
             absent=["{O}/out.png"])
