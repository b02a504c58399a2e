"""scripts/make_big_scene.py without a GPU: the copies add up to the triangles asked for, the ones
in view are the same whatever the total, and the hidden ones lie behind the wall or behind the
camera. Run from the repository root: python3 -m unittest discover -s tests/bench"""
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SPHERE_TRIANGLES = 4096  # engine/scene/primitives: makeSphere(0.5, 64, 32)


def make(directory, *args):
    out = os.path.join(directory, "big.json")
    subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_big_scene.py"), "--model", "sphere",
                    "--out", out, *args], check=True, capture_output=True)
    with open(out) as f:
        return json.load(f)


def placements(scene, name):
    model = next(m for m in scene["models"] if m["name"] == name)
    return [p["translate"] for p in model.get("instances", [{"translate": model.get("translate", [0, 0, 0])}])]


def copies(scene):
    return sum(len(m["instances"]) if "instances" in m else 1
               for m in scene["models"] if m.get("primitive") == "sphere")


class BigScene(unittest.TestCase):
    def test_copies_add_up_and_the_view_does_not_depend_on_the_total(self):
        with tempfile.TemporaryDirectory() as d:
            small = make(d, "--triangles", "400k", "--visible-triangles", "100k")
            large = make(d, "--triangles", "4M", "--visible-triangles", "100k")
        self.assertEqual(copies(small), 400000 // SPHERE_TRIANGLES)
        self.assertEqual(copies(large), 4000000 // SPHERE_TRIANGLES)
        self.assertEqual(small["camera"], large["camera"])
        in_view = lambda s: [m for m in s["models"] if not m["name"].startswith("hidden")]
        self.assertEqual(in_view(small), in_view(large))
        self.assertEqual(len(placements(small, "visible")) + 8, 100000 // SPHERE_TRIANGLES)
        self.assertEqual(sum("spin" in m for m in small["models"]), 8)

    def test_hidden_copies_are_behind_the_wall_or_the_camera_and_the_visible_ones_in_view(self):
        with tempfile.TemporaryDirectory() as d:
            scene = make(d, "--triangles", "2M", "--visible-triangles", "200k")
        camera = scene["camera"]
        wall = next(m for m in scene["models"] if m["name"] == "wall")
        wall_front = wall["translate"][2] + 0.5 * wall["scale"][2]
        wall_back = wall["translate"][2] - 0.5 * wall["scale"][2]
        # Behind the wall: seen from the camera, within the angle the wall covers.
        wall_half_angle = math.atan2(0.5 * wall["scale"][0], camera["position"][2] - wall_front)
        for p in placements(scene, "hidden_behind_wall"):
            self.assertLess(p[2] + 0.5, wall_back, p)
            self.assertLess(math.atan2(abs(p[0]) + 0.5, camera["position"][2] - p[2]), wall_half_angle, p)
        for p in placements(scene, "hidden_behind_camera"):
            self.assertGreater(p[2] - 0.5, camera["position"][2], p)
        # The copies in view lie between the camera and the wall, inside a 16:9 view's horizontal angle.
        half_width = math.atan(math.tan(math.radians(camera["fov"] / 2)) * 16 / 9)
        in_view = placements(scene, "visible") + [m["translate"] for m in scene["models"] if "spin" in m]
        for p in in_view:
            self.assertGreater(p[2] - 0.5, wall_front, p)
            ahead = camera["position"][2] - p[2]
            self.assertGreater(ahead, 0.0, p)
            self.assertLess(math.atan2(abs(p[0]) + 0.5, ahead), half_width, p)
        # The wall's top hides what lies behind it from the camera's height.
        self.assertGreater(wall["translate"][1] + 0.5 * wall["scale"][1], camera["position"][1] + 1.0)

    def test_moving_unless_still(self):
        with tempfile.TemporaryDirectory() as d:
            moving = make(d, "--triangles", "200k", "--visible-triangles", "100k")
            still = make(d, "--triangles", "200k", "--visible-triangles", "100k", "--still")
        self.assertIn("turn", moving["lights"][0])
        self.assertEqual(sum("spin" in m for m in moving["models"]), 8)
        self.assertNotIn("turn", still["lights"][0])
        self.assertFalse(any("spin" in m for m in still["models"]))
        self.assertEqual(copies(moving), copies(still))


if __name__ == "__main__":
    unittest.main()
