#!/usr/bin/env python3
"""Times Google Filament (through the `filly` wheel: Filament embedded, headless EGL) on a scene that
bench/peers/scene_to_glb.py converted: the GLB, the same camera and size, the sidecar's sun (one shadow
cascade, Filament's default; map size --shadow-size), its point lights, IBL and visible sky from the
same HDR map; bloom, AA, MSAA, SSAO, dithering, fog off. After --warmup frames it renders until
Filament has reported --frames GPU frame times (renderer.stats.gpu_frame_ms, Filament's own timer
queries, with a few frames of latency) and writes their median to JSON.

  filament.py NAME.peer.json --size 1920x1080 --frames 200 --warmup 30 --out filament.json [--image out.png]

Light units: lightpass's are relative to its exposure; Filament's are photometric (lux, candela) under
the camera's exposure (EV100 = camera.exposure, default f/16 1/125 s ISO 100). Each intensity is
multiplied by 1.2 * 2^EV100, the factor Filament's exposure divides by, so a lightpass intensity 1
sun lights as brightly in both. Needs Python >= 3.12 with filly and numpy.
"""
import argparse
import json
import os
import statistics
import struct
import sys
import time
import zlib


class PeerError(Exception):
    pass


def parse_size(text):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--size {text}: expected WxH, e.g. 1920x1080")
    if not (1 <= w <= 8192 and 1 <= h <= 8192):
        raise argparse.ArgumentTypeError(f"--size {text}: each side must be 1..8192")
    return w, h


def load_sidecar(path):
    """The converter's NAME.peer.json, with the GLB path made absolute; one-line errors."""
    try:
        with open(path, encoding="utf-8") as f:
            side = json.load(f)
    except FileNotFoundError:
        raise PeerError(f"{path}: file not found")
    except json.JSONDecodeError as e:
        raise PeerError(f"{path}: invalid JSON: {e}")
    for key in ("glb", "camera", "suns", "points"):
        if key not in side:
            raise PeerError(f"{path}: {key}: missing (write it with bench/peers/scene_to_glb.py)")
    side["glb"] = os.path.join(os.path.dirname(os.path.abspath(path)), side["glb"])
    if not os.path.isfile(side["glb"]):
        raise PeerError(f"{path}: glb {side['glb']}: file not found")
    env = side.get("environment")
    if env and not os.path.isfile(env["map"]):
        raise PeerError(f"{path}: environment.map {env['map']}: file not found")
    return side


# Where an equirectangular map's centre column faces: lightpass -Z (shaders/common/ibl.glsl, where its
# default camera looks), Filament through filly's load_environment +Z. Both read the map unmirrored
# from inside (measured with filly 0.2.1: a map of coloured patches seen from the origin shows them
# as in the flat image, at +Z in Filament, at -Z in lightpass), and both rotate it right-handed about
# +Y, so the same map lines up in both with half a turn more in Filament.
FILAMENT_ENVIRONMENT_TURN_DEG = 180.0


# How far (in scene sizes) the point light standing for an extracted environment light is placed.
ENV_LIGHT_DISTANCE = 1000.0


def filament_environment_rotation(lightpass_rotation_deg):
    """Filament's environment_rotation_deg that shows the map as lightpass's `rotation` does."""
    return lightpass_rotation_deg + FILAMENT_ENVIRONMENT_TURN_DEG


def photometric_scale(ev100):
    """Lux (or candela) per lightpass intensity unit: 1 / Filament's exposure factor 1 / (1.2 * 2^EV100)."""
    return 1.2 * 2.0 ** ev100


def collect_gpu_times(render, stats, frames, warmup, max_renders):
    """Renders `warmup` frames, then renders until `frames` GPU times of frames after the warm-up have
    been reported or `max_renders` more renders were made. `stats()` returns (gpu_frame_ms,
    gpu_frame_number), either None until Filament has a measurement; each frame number counts once.
    Returns the times in ms, in frame order."""
    for _ in range(warmup):
        render()
    _, last = stats()
    times, seen = [], set()
    renders = 0
    while len(times) < frames and renders < max_renders:
        render()
        renders += 1
        ms, number = stats()
        if ms is None or number is None or number in seen or (last is not None and number <= last):
            continue
        seen.add(number)
        times.append(float(ms))
    return times


def summary(times):
    s = sorted(times)
    pick = lambda q: s[min(len(s) - 1, int(q * (len(s) - 1) + 0.5))]
    return {"median_ms": statistics.median(s), "p10_ms": pick(0.1), "p90_ms": pick(0.9), "min_ms": s[0], "max_ms": s[-1]}


def write_png(path, rgba):
    """An RGBA8 image (rows top first, as RenderTarget.read() returns them) as PNG."""
    h, w = rgba.shape[0], rgba.shape[1]
    raw = b"".join(b"\x00" + rgba[y].tobytes() for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def build_scene(filly, renderer, side, width, height, shadow_size, tone_mapping):
    """The sidecar's scene in filly; returns (scene, settings record)."""
    scene = renderer.create_scene()
    scene.load(side["glb"])
    cam = side["camera"]
    camera = renderer.create_camera()
    camera.set_perspective(fov_y_deg=cam["fov"], aspect=width / height, near=cam["near"], far=cam["far"])
    camera.position = cam["position"]
    camera.look_at(cam["target"], up=cam["up"])
    scene.camera = camera
    scale = photometric_scale(camera.exposure)

    for sun in side["suns"]:
        light = scene.add_directional_light(direction=sun["direction"], intensity=sun["intensity"] * scale,
                                            color=sun["color"])
        light.casts_shadows = bool(sun.get("shadows", True))
        light.shadow_map_size = shadow_size
    for p in side["points"]:
        if p.get("type") == "spot":
            scene.add_spot_light(position=p["position"], direction=p["direction"], intensity=p["intensity"] * scale,
                                 color=p["color"], range=p["range"], cone_deg=[p["innerAngle"], p["outerAngle"]])
        else:
            scene.add_point_light(position=p["position"], intensity=p["intensity"] * scale, color=p["color"],
                                  range=p["range"])
    env = side.get("environment")
    if env:
        scene.environment = renderer.load_environment(env["map"])
        scene.environment_intensity = env["intensity"] * scale
        scene.environment_rotation_deg = filament_environment_rotation(env.get("rotation", 0.0))
        scene.environment_visible = True
        # The map's sources that scene_to_glb.py took out of it (lightpass's extracted lights), unshadowed
        # (lightpass shades them as IBL), at the environment's intensity. Filament draws one directional
        # light (the scene's sun), so each is a point light ENV_LIGHT_DISTANCE scene sizes away in its
        # direction, its candela giving the same irradiance at the scene (within 0.1%), its range far beyond.
        lo, hi = side.get("bounds", [[0, 0, 0], [1, 1, 1]])
        centre = [(a + b) / 2 for a, b in zip(lo, hi)]
        far = ENV_LIGHT_DISTANCE * max(1.0, max(b - a for a, b in zip(lo, hi)))
        for l in env.get("lights", []):
            e = l["irradiance"]
            peak = max(e)
            scene.add_point_light(position=[c + far * t for c, t in zip(centre, l["towards"])],
                                  intensity=peak * far * far * env["intensity"] * scale,
                                  color=[x / peak for x in e], range=10.0 * far)

    scene.shadows = any(s.get("shadows", True) for s in side["suns"])
    scene.bloom = False
    scene.ssao = False
    scene.antialiasing = "none"
    scene.msaa = 1
    scene.dithering = False
    scene.fog = False
    scene.depth_of_field = False
    scene.vignette = False
    scene.tone_mapping = tone_mapping
    settings = {"suns": len(side["suns"]), "shadow_cascades": 1, "shadow_map_size": shadow_size,
                "local_lights": len(side["points"]), "ibl": bool(env), "sky": bool(env),
                "environment_map": env["map"] if env else None,
                "environment_rotation_deg": filament_environment_rotation(env.get("rotation", 0.0)) if env else None,
                "tone_mapping": tone_mapping,
                "output_path": scene.output_path, "bloom": False, "ssao": False, "antialiasing": "none", "msaa": 1,
                "exposure_ev100": camera.exposure, "lux_per_lightpass_unit": scale}
    return scene, settings


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sidecar", help="NAME.peer.json from bench/peers/scene_to_glb.py")
    ap.add_argument("--size", type=parse_size, default=(1920, 1080))
    ap.add_argument("--frames", type=int, default=200, help="GPU frame times to take the median of")
    ap.add_argument("--warmup", type=int, default=30)
    ap.add_argument("--shadow-size", type=int, default=2048, help="texels per side of the sun's one cascade")
    ap.add_argument("--tone-mapping", default="aces", help="Filament's tone mapper (lightpass: --tonemap aces)")
    ap.add_argument("--sync-every", type=int, default=2,
                    help="renderer.finish() after every N frames: Filament's timer queue drops frames when the "
                         "GPU falls further behind (default 2: two frames in flight)")
    ap.add_argument("--out", required=True, help="JSON to write")
    ap.add_argument("--image", help="also write the last frame as PNG")
    a = ap.parse_args(argv)
    if a.frames < 1 or a.warmup < 0 or a.sync_every < 1:
        ap.error("--frames and --sync-every must be >= 1, --warmup >= 0")
    try:
        side = load_sidecar(a.sidecar)
        try:
            import filly
        except ImportError as e:
            raise PeerError(f"cannot import filly ({e}); see bench/peers/README.md (Python >= 3.12, the peers-wheels folder)")
        if hasattr(filly, "set_log_level"):
            filly.set_log_level("warning")
        width, height = a.size
        started = time.time()
        with filly.Renderer() as renderer:
            scene, settings = build_scene(filly, renderer, side, width, height, a.shadow_size, a.tone_mapping)
            target = renderer.create_render_target(width=width, height=height)
            load_s = time.time() - started

            rendered = [0]

            def render():
                renderer.render(scene, target)
                rendered[0] += 1
                if rendered[0] % a.sync_every == 0:
                    renderer.finish()

            def stats():
                s = renderer.stats
                return s.gpu_frame_ms, s.gpu_frame_number

            times = collect_gpu_times(render, stats, a.frames, a.warmup, max_renders=20 * a.frames + 100)
            renderer.finish()
            if a.image:
                write_png(a.image, target.read())
            platform = renderer.gl_platform
        if not times:
            raise PeerError("Filament reported no GPU frame time (renderer.stats.gpu_frame_ms stayed None)")
        result = {"renderer": "filament", "filly_version": getattr(filly, "__version__", "?"), "gl_platform": platform,
                  "scene": side.get("scene"), "glb": side["glb"], "triangles": side.get("triangles"),
                  "width": width, "height": height, "warmup": a.warmup, "frames_requested": a.frames,
                  "frames": len(times), "sync_every": a.sync_every, "gpu_frame_ms": summary(times), "samples_ms": times, "settings": settings,
                  "load_s": load_s}
        if len(times) < a.frames:
            print(f"filament.py: warning: {len(times)} of {a.frames} GPU frame times reported", file=sys.stderr)
        tmp = a.out + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            json.dump(result, f, indent=1)
        os.replace(tmp, a.out)
        print(f"filament {os.path.basename(a.sidecar)} {width}x{height}: median {result['gpu_frame_ms']['median_ms']:.3f} ms "
              f"GPU over {len(times)} frames -> {a.out}")
        return 0
    except PeerError as e:
        print(f"filament.py: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
