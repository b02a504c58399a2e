#!/usr/bin/env python3
"""check_viewport.py WITH_PANEL.png IMAGE_X WITHOUT_PANEL.png: the viewer's window read back with the
panel shown (the image beside it, from x = IMAGE_X) and hidden (the image filling the window), on
scenes/cornell.json. The box's red and green walls locate the image: with the panel none of their
pixels lies under it and the box is centred in the region right of it; without, centred in the
window. The walls' distance is the same in both (same height, same vertical field of view): the
camera's aspect followed the viewport instead of squeezing a window-wide image into it."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_pixel import read_png


def walls(path):
    w, h, bpp, rows = read_png(path)
    red, green = [], []
    for y in range(0, h, 4):
        row = rows[y]
        for x in range(w):
            r, g, b = row[x * bpp], row[x * bpp + 1], row[x * bpp + 2]
            if r > 40 and r > 2 * g and r > 2 * b:
                red.append(x)
            elif g > 50 and g > 1.5 * r and g > 2 * b:
                green.append(x)
    assert len(red) > 100 and len(green) > 100, f"{path}: no red and green walls ({len(red)}, {len(green)} texels)"
    return w, h, red, green


with_panel, image_x, without_panel = sys.argv[1], int(float(sys.argv[2])), sys.argv[3]
w, h, red, green = walls(with_panel)
assert min(red + green) >= image_x, f"{with_panel}: a wall texel at x = {min(red + green)}, under the panel (< {image_x})"
centre = (sum(red) / len(red) + sum(green) / len(green)) / 2
want = image_x + (w - image_x) / 2
assert abs(centre - want) < 8, f"{with_panel}: the box is centred at x = {centre:.1f}, not the viewport's {want:.1f}"
spread = sum(green) / len(green) - sum(red) / len(red)
w2, h2, red2, green2 = walls(without_panel)
centre2 = (sum(red2) / len(red2) + sum(green2) / len(green2)) / 2
assert abs(centre2 - w2 / 2) < 8, f"{without_panel}: the box is centred at x = {centre2:.1f}, not the window's {w2 / 2}"
spread2 = sum(green2) / len(green2) - sum(red2) / len(red2)
assert abs(spread / spread2 - 1) < 0.03, f"walls {spread:.1f} px apart beside the panel, {spread2:.1f} px in the whole window"
print(f"viewport ok: box centred at {centre:.1f} (viewport centre {want:.1f}) beside the panel, {centre2:.1f} without; "
      f"walls {spread:.1f} and {spread2:.1f} px apart")
