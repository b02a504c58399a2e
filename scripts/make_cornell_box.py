#!/usr/bin/env python3
"""Writes models/cornell_box.obj/.mtl from the Cornell box's published measurements.

Source: Cornell University Program of Computer Graphics, "Cornell Box Data"
(www.graphics.cornell.edu/online/box/data.html): vertex coordinates in millimetres, the camera at
(278, 273, -800) looking along +z with a 35 mm lens and a 25 mm x 25 mm film (vertical field of view
2*atan(12.5/35) = 39.3 degrees), and the wall reflectances measured per wavelength. The reflectances
here are the usual RGB reductions of those spectra.

Output is in metres (x0.001) so the box is 0.556 m wide. The box's open side faces -z.
"""
import os
import sys

WHITE, RED, GREEN, LIGHT = "white", "red", "green", "light"
MATERIALS = {
    WHITE: (0.725, 0.71, 0.68),
    RED: (0.63, 0.065, 0.05),
    GREEN: (0.14, 0.45, 0.091),
    LIGHT: (0.78, 0.78, 0.78),
}

# Quads in the published order; each is (material, [4 vertices in mm]).
QUADS = [
    (WHITE, [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]),            # floor
    (LIGHT, [(343, 548.7, 227), (343, 548.7, 332), (213, 548.7, 332), (213, 548.7, 227)]),  # light patch, just below the ceiling
    (WHITE, [(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]),  # ceiling
    (WHITE, [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]),  # back wall
    (GREEN, [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]),            # right wall
    (RED, [(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]),  # left wall
    # short block
    (WHITE, [(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)]),
    (WHITE, [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)]),
    (WHITE, [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)]),
    (WHITE, [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)]),
    (WHITE, [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)]),
    # tall block
    (WHITE, [(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)]),
    (WHITE, [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)]),
    (WHITE, [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)]),
    (WHITE, [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)]),
    (WHITE, [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)]),
]


def main(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    obj = ["# Cornell box from the published measurements (metres); written by scripts/make_cornell_box.py",
           "mtllib cornell_box.mtl"]
    index = 1
    current = None
    for material, quad in QUADS:
        if material != current:
            obj.append(f"usemtl {material}")
            current = material
        for x, y, z in quad:
            obj.append(f"v {x * 0.001:.4f} {y * 0.001:.4f} {z * 0.001:.4f}")
        obj.append(f"f {index} {index + 1} {index + 2} {index + 3}")
        index += 4
    mtl = ["# Cornell box materials: RGB reductions of the measured reflectances"]
    for name, (r, g, b) in MATERIALS.items():
        mtl += [f"newmtl {name}", f"Kd {r} {g} {b}", "Ks 0 0 0", "Ns 10", ""]
    for path, lines in (("cornell_box.obj", obj), ("cornell_box.mtl", mtl)):
        tmp = os.path.join(out_dir, path + ".tmp")
        with open(tmp, "w") as f:
            f.write("\n".join(lines) + "\n")
        os.replace(tmp, os.path.join(out_dir, path))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "models"))
