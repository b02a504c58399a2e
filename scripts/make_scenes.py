#!/usr/bin/env python3
"""Writes the generated bundled scenes: scenes/gallery.json (256 local lights),
scenes/ibl-spheres.json (a material grid), scenes/lights-4k.json (4096 local lights) and
scenes/instanced-grid.json (one model drawn 48 times). Deterministic (fixed seed), so re-running changes nothing.

gallery: the Stanford bunny, dragon and Happy Buddha (from ../shared/assets) on a floor, two suns with
shadows, 256 ranged point lights orbiting above the floor, and an HDR sky.
ibl-spheres: 7 x 3 spheres, roughness (shininess) across, specular up, under an HDR map, no local lights.
lights-4k: the bundled Cornell box with two spheres lit by 4096 small ranged point lights and nothing
else: no sun, no shadows, no environment map (so the graph has no shadow, IBL or sky pass).
instanced-grid: the bundled Cornell box as one model with 48 "instances" (an 8 x 6 grid, each turned
and scaled a little), stored once and drawn 48 times, on a floor under a sun with shadows and the sky.
"""
import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "scenes")
ASSETS = "../../shared/assets"


def write(name, scene):
    path = os.path.join(SCENES, name)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def gallery():
    rng = random.Random(562)
    lights = [
        {"type": "directional", "direction": [-0.4, -1.0, -0.3], "color": [1.0, 0.95, 0.85], "intensity": 2.5, "shadows": True},
        {"type": "directional", "direction": [0.6, -0.8, 0.4], "color": [0.6, 0.7, 1.0], "intensity": 0.8, "shadows": True},
    ]
    for i in range(256):
        a = rng.uniform(0, 2 * math.pi)
        r = rng.uniform(0.5, 5.5)
        h = rng.uniform(0.15, 1.6)
        hue = rng.random()
        c = [0.5 + 0.5 * math.cos(2 * math.pi * (hue + k / 3.0)) for k in range(3)]
        lights.append({"type": "point", "position": [round(r * math.cos(a), 3), round(h, 3), round(r * math.sin(a), 3)],
                       "color": [round(x, 3) for x in c], "intensity": round(rng.uniform(0.05, 0.25), 3),
                       "range": round(rng.uniform(0.6, 1.4), 3),
                       "orbit": {"center": [0, round(h, 3), 0], "speed": round(rng.uniform(-0.4, 0.4), 3)}})
    return {
        "description": "Stanford models from ../shared/assets on a floor, two suns with shadows, 256 local lights, HDR sky. Needs ../shared/assets.",
        "camera": {"position": [0.0, 2.6, 7.5], "target": [0.0, 0.8, 0.0], "fov": 45, "near": 0.05, "far": 60},
        "models": [
            {"name": "floor", "primitive": "plane", "scale": [14, 1, 14], "material": {"diffuse": [0.55, 0.55, 0.52], "specular": [0.04, 0.04, 0.04], "shininess": 32}},
            {"name": "bunny", "obj": f"{ASSETS}/stanford-bunny/stanford-bunny.obj", "translate": [-2.4, -0.33, 0.3], "scale": 10.0,
             "material": {"diffuse": [0.8, 0.75, 0.7], "specular": [0.2, 0.2, 0.2], "shininess": 64}},
            {"name": "dragon", "obj": f"{ASSETS}/stanford-dragon/dragon.obj", "translate": [0.0, 0.0, -0.2], "scale": 0.16,
             "material": {"diffuse": [0.35, 0.6, 0.3], "specular": [0.5, 0.5, 0.5], "shininess": 128}},
            {"name": "buddha", "obj": f"{ASSETS}/stanford-happy-buddha/buddha.obj", "translate": [2.4, 0.0, 0.2], "rotate": [0, 180, 0], "scale": 0.02,
             "material": {"diffuse": [0.85, 0.7, 0.4], "specular": [0.6, 0.55, 0.4], "shininess": 256}},
        ],
        "lights": lights,
        "environment": {"map": f"{ASSETS}/hdri-polyhaven-1k/pedestrian_overpass_1k.hdr", "intensity": 1.0, "ibl": True},
        "ambient": [0.02, 0.02, 0.02],
    }


def ibl_spheres():
    models = []
    shininess = [2, 8, 32, 128, 512, 2048, 8192]
    for row, spec in enumerate([0.04, 0.3, 1.0]):
        for col, n in enumerate(shininess):
            models.append({"name": f"sphere_r{row}_c{col}", "primitive": "sphere",
                           "translate": [round((col - 3) * 1.2, 3), round(row * 1.2, 3), 0.0],
                           "material": {"diffuse": [0.8, 0.8, 0.8] if row == 0 else [0.2, 0.2, 0.2],
                                        "specular": [spec, spec, spec], "shininess": n}})
    return {
        "description": "Material grid under an HDR map, no local lights: shininess (GGX roughness) across, specular up.",
        "camera": {"position": [0.0, 1.2, 9.5], "target": [0.0, 1.2, 0.0], "fov": 45, "near": 0.1, "far": 50},
        "models": models,
        "lights": [],
        "environment": {"map": "../hdr/sky.hdr", "intensity": 1.0, "ibl": True},
        "ambient": [0.0, 0.0, 0.0],
    }


def lights_4k():
    rng = random.Random(4096)
    lights = []
    for i in range(4096):
        hue = rng.random()
        c = [0.5 + 0.5 * math.cos(2 * math.pi * (hue + k / 3.0)) for k in range(3)]
        # inside the box (0..0.556 m in x and z, 0..0.549 m in y), kept off the walls
        p = [rng.uniform(0.02, 0.536), rng.uniform(0.02, 0.529), rng.uniform(0.02, 0.54)]
        lights.append({"type": "point", "position": [round(x, 4) for x in p], "color": [round(x, 3) for x in c],
                       "intensity": round(rng.uniform(0.0005, 0.002), 5), "range": round(rng.uniform(0.04, 0.09), 4)})
    return {
        "description": "The Cornell box lit only by 4096 small ranged point lights: no sun, no shadows, no environment map.",
        "camera": {"position": [0.278, 0.273, -0.8], "target": [0.278, 0.273, 0.0], "fov": 39.3, "near": 0.05, "far": 3.0},
        "models": [
            {"name": "cornell_box", "obj": "../models/cornell_box.obj"},
            {"name": "glossy_sphere", "primitive": "sphere", "translate": [0.185, 0.245, 0.169], "scale": 0.16,
             "material": {"diffuse": [0.9, 0.9, 0.9], "specular": [0.6, 0.6, 0.6], "shininess": 256}},
            {"name": "blue_sphere", "primitive": "sphere", "translate": [0.42, 0.06, 0.11], "scale": 0.12,
             "material": {"diffuse": [0.1, 0.25, 0.8], "specular": [0.3, 0.3, 0.3], "shininess": 64}},
        ],
        "lights": lights,
        "environment": {"color": [0.0, 0.0, 0.0]},
        "ambient": [0.005, 0.005, 0.005],
    }


def instanced_grid():
    rng = random.Random(4848)
    instances = []
    for row in range(6):
        for col in range(8):
            instances.append({
                "translate": [round((col - 3.5) * 0.7, 3), 0.0, round(-row * 0.7, 3)],
                "rotate": [0, round(rng.uniform(-180.0, 180.0), 1), 0],
                "scale": round(rng.uniform(0.8, 1.1), 3),
            })
    return {
        "description": "One model, many copies: the bundled Cornell box stored once and drawn at 48 placements "
                       "(models[].instances), an 8 x 6 grid on a floor under a sun with shadows and the sky.",
        "camera": {"position": [0.0, 2.6, 3.2], "target": [0.0, 0.0, -1.6], "fov": 50, "near": 0.1, "far": 40},
        "models": [
            {"name": "boxes", "obj": "../models/cornell_box.obj", "scale": 0.8, "translate": [-0.222, 0, -0.222],
             "instances": instances},
            {"name": "floor", "primitive": "plane", "scale": [12, 1, 10], "translate": [0, 0, -1.7],
             "material": {"diffuse": [0.45, 0.45, 0.45], "specular": [0.04, 0.04, 0.04], "roughness": 0.7}},
        ],
        "lights": [{"type": "directional", "direction": [-0.5, -1.0, -0.35], "intensity": 2.5, "shadows": True}],
        "environment": {"map": "../hdr/sky.hdr", "intensity": 0.6, "ibl": True},
    }


if __name__ == "__main__":
    write("gallery.json", gallery())
    write("ibl-spheres.json", ibl_spheres())
    write("lights-4k.json", lights_4k())
    write("instanced-grid.json", instanced_grid())
