#!/usr/bin/env python3
"""Writes scene.json: a furnished room lit only by a window (an area source in the back wall).

Run from this folder: python3 make_scene.py > scene.json. Metres; y is up."""
import json

W, H, D = 4.0, 2.7, 5.0                 # room width (x), height (y), depth (z)
WIN = (1.2, 2.8, 0.9, 2.1)              # window in the back wall z = D: x0, x1, y0, y1


def sub(a, b): return [a[i] - b[i] for i in range(3)]
def cross(a, b): return [a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0]]
def dot(a, b): return sum(a[i]*b[i] for i in range(3))


def quad(corners, normal):
    """The four corners counter-clockwise seen from the side `normal` points to."""
    n = cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]))
    return corners if dot(n, normal) > 0 else corners[::-1]


def rect(axis, value, lo, hi, normal):
    """Axis-aligned rectangle in the plane coordinate[axis] = value; lo, hi bound the other two."""
    u, v = [i for i in range(3) if i != axis]
    def p(a, b):
        q = [0.0] * 3
        q[axis], q[u], q[v] = value, a, b
        return q
    return quad([p(lo[0], lo[1]), p(hi[0], lo[1]), p(hi[0], hi[1]), p(lo[0], hi[1])], normal)


def box(x0, x1, y0, y1, z0, z1, skip=()):
    """The faces of a box, fronts outward; `skip` names faces left out (resting on or touching
    something): -x, +x, -y, +y, -z, +z."""
    faces = {
        '-x': rect(0, x0, (y0, z0), (y1, z1), [-1, 0, 0]),
        '+x': rect(0, x1, (y0, z0), (y1, z1), [1, 0, 0]),
        '-y': rect(1, y0, (x0, z0), (x1, z1), [0, -1, 0]),
        '+y': rect(1, y1, (x0, z0), (x1, z1), [0, 1, 0]),
        '-z': rect(2, z0, (x0, y0), (x1, y1), [0, 0, -1]),
        '+z': rect(2, z1, (x0, y0), (x1, y1), [0, 0, 1]),
    }
    return [f for k, f in faces.items() if k not in skip]


x0, x1, y0, y1 = WIN
objects = [
    {"name": "floor", "material": "oak", "polygons": [rect(1, 0, (0, 0), (W, D), [0, 1, 0])]},
    {"name": "ceiling", "material": "plaster", "polygons": [rect(1, H, (0, 0), (W, D), [0, -1, 0])]},
    {"name": "left wall", "material": "plaster", "polygons": [rect(0, 0, (0, 0), (H, D), [1, 0, 0])]},
    {"name": "right wall", "material": "blue paint", "polygons": [rect(0, W, (0, 0), (H, D), [-1, 0, 0])]},
    {"name": "front wall", "material": "plaster", "polygons": [rect(2, 0, (0, 0), (W, H), [0, 0, 1])]},
    # The back wall around the window's opening: four rectangles, as the Cornell box's ceiling
    # around its light (no two polygons overlap; the window fills the opening).
    {"name": "back wall", "material": "plaster", "polygons": [
        rect(2, D, (0, 0), (x0, H), [0, 0, -1]),
        rect(2, D, (x1, 0), (W, H), [0, 0, -1]),
        rect(2, D, (x0, 0), (x1, y0), [0, 0, -1]),
        rect(2, D, (x0, y1), (x1, H), [0, 0, -1])]},
    {"name": "window", "material": "sky", "polygons": [rect(2, D, (x0, y0), (x1, y1), [0, 0, -1])]},
    # A table: a 1.2 x 0.8 top 40 mm thick at 0.75 m, on four 50 mm legs.
    {"name": "table top", "material": "walnut", "polygons": box(1.4, 2.6, 0.71, 0.75, 2.6, 3.4)},
    {"name": "table legs", "material": "walnut", "polygons":
        [f for (lx, lz) in ((1.45, 2.65), (2.5, 2.65), (1.45, 3.3), (2.5, 3.3))
         for f in box(lx, lx + 0.05, 0, 0.71, lz, lz + 0.05, skip=('-y', '+y'))]},
    # A low cabinet against the right wall and a tall bookcase against the left wall.
    {"name": "cabinet", "material": "white lacquer", "polygons": box(3.55, W, 0, 0.6, 1.0, 2.6, skip=('-y', '+x'))},
    {"name": "bookcase", "material": "walnut", "polygons": box(0, 0.35, 0, 2.0, 3.2, 4.4, skip=('-y', '-x'))},
]
materials = {
    "oak": {"reflectance": [0.45, 0.33, 0.22]},
    "plaster": {"reflectance": [0.78, 0.76, 0.72]},
    "blue paint": {"reflectance": [0.25, 0.35, 0.55]},
    "walnut": {"reflectance": [0.30, 0.20, 0.13]},
    "white lacquer": {"reflectance": [0.80, 0.80, 0.78]},
    # Overcast daylight through the opening: radiant exitance, W/m^2; the opening itself
    # reflects nothing (light leaving through it is lost outside).
    "sky": {"reflectance": [0, 0, 0], "emission": [80, 90, 100]},
}
camera = {"eye": [2.0, 1.5, 0.3], "look_at": [2.0, 1.1, 5.0], "up": [0, 1, 0],
          "fov_deg": 65, "width": 512, "height": 384}
print(json.dumps({"materials": materials, "objects": objects, "camera": camera}, indent=1))
