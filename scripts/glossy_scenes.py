#!/usr/bin/env python3
"""Writes data/glossy-ring/ and data/cornell-glossy-pane/ (issue 20). The ring (paper 003 Fig. 2): a ring of brushed metal standing on a
white floor under a point light, whose inside reflects the light onto the floor as a blurred
cardioid. The ring is a mesh (ring.obj: SEGMENTS quads inside, facing the axis, and as many
outside, facing out) marked "smooth", so its glossy beams are warped by vertex normals as a
round ring's would be. Also ring-points.csv, a line of floor points across the caustic.
The pane (003 Fig. 13): the Cornell box of data/cornell-glass-mirror/ with one roughened pane
(transmittance with gloss) under the light in place of its four tinted ones, and no mirror.
Usage: python3 scripts/glossy_scenes.py"""
import json
import math
import os

OUT = os.path.join(os.path.dirname(__file__), "..", "data", "glossy-ring")
SEGMENTS = 40
RADIUS, HEIGHT, WALL = 1.0, 0.45, 0.03


def ring_obj():
    lines = ["# a ring of radius %g, height %g: %d quads inside (facing the axis), %d outside"
             % (RADIUS, HEIGHT, SEGMENTS, SEGMENTS)]
    for r in (RADIUS, RADIUS + WALL):
        for k in range(SEGMENTS):
            a = 2 * math.pi * k / SEGMENTS
            for z in (0.0, HEIGHT):
                lines.append("v %.9f %.9f %.9f" % (r * math.cos(a), r * math.sin(a), z))
    inner, outer = 0, 2 * SEGMENTS

    def v(base, k, top):
        return base + 2 * (k % SEGMENTS) + top + 1

    # Inside: counter-clockwise seen from the axis. Outside: seen from outside. Top: a rim.
    for k in range(SEGMENTS):
        lines.append("f %d %d %d %d" % (v(inner, k, 0), v(inner, k, 1), v(inner, k + 1, 1),
                                        v(inner, k + 1, 0)))
    for k in range(SEGMENTS):
        lines.append("f %d %d %d %d" % (v(outer, k, 0), v(outer, k + 1, 0), v(outer, k + 1, 1),
                                        v(outer, k, 1)))
    return "\n".join(lines) + "\n"


def rim_polygons():
    rims = []
    for k in range(SEGMENTS):
        a, b = 2 * math.pi * k / SEGMENTS, 2 * math.pi * (k + 1) / SEGMENTS
        p = lambda r, t: [round(r * math.cos(t), 9), round(r * math.sin(t), 9), HEIGHT]
        rims.append([p(RADIUS, a), p(RADIUS + WALL, a), p(RADIUS + WALL, b), p(RADIUS, b)])
    return rims


def main():
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "ring.obj"), "w") as f:
        f.write(ring_obj())
    scene = {
        "materials": {
            "floor": {"reflectance": [0.75, 0.75, 0.72]},
            "brushed gold": {"reflectance": [0.05, 0.04, 0.02], "specular": [0.9, 0.75, 0.4],
                             "gloss": 0.08},
            "rim": {"reflectance": [0.3, 0.25, 0.15]},
        },
        "objects": [
            {"name": "floor", "material": "floor",
             "polygons": [[[-2.5, -2.5, 0], [2.5, -2.5, 0], [2.5, 2.5, 0], [-2.5, 2.5, 0]]]},
            {"name": "ring", "mesh": "ring.obj", "material": "brushed gold", "smooth": True},
            {"name": "rim", "material": "rim", "polygons": rim_polygons()},
        ],
        "lights": [{"position": [-2.2, 0.0, 1.1], "intensity": [6.0, 6.0, 6.0]}],
        "camera": {"eye": [0.3, -2.6, 3.2], "look_at": [0.1, 0.0, 0.0], "up": [0, 0, 1],
                   "fov_deg": 45, "width": 256, "height": 256},
    }
    with open(os.path.join(OUT, "scene.json"), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
    with open(os.path.join(OUT, "ring-points.csv"), "w") as f:
        f.write("x,y,z,nx,ny,nz\n")
        for i in range(33):
            x = -0.8 + 1.6 * i / 32
            f.write("%.6f,0,0,0,0,1\n" % x)


def cornell_pane():
    here = os.path.join(os.path.dirname(__file__), "..", "data")
    with open(os.path.join(here, "cornell-glass-mirror", "scene.json")) as f:
        glass = json.load(f)
    materials = {k: v for k, v in glass["materials"].items()
                 if k in ("white", "red", "green", "light")}
    materials["frosted glass"] = {"reflectance": 0.04, "transmittance": [0.85, 0.8, 0.7],
                                  "gloss": 0.12}
    keep = ("floor", "ceiling", "light", "back wall", "right wall", "left wall", "short block",
            "tall block")
    objects = [o for o in glass["objects"] if o["name"] in keep]
    y = 440.0  # under the light, facing down (counter-clockwise seen from below)
    objects.append({"name": "frosted pane", "material": "frosted glass",
                    "polygons": [[[170, y, 180], [390, y, 180], [390, y, 380], [170, y, 380]]]})
    scene = {"materials": materials, "objects": objects}
    for key in ("camera", "mirror_depth", "refraction_depth"):
        if key in glass:
            scene[key] = glass[key]
    out = os.path.join(here, "cornell-glossy-pane")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
    cornell_pane()
