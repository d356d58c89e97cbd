#!/usr/bin/env python3
"""Writes the refraction benchmark scenes of data/refraction/ (issue 19, paper 000 §4): a room of
the Cornell box's size with black walls (so that only the lamp's light, straight or refracted,
reaches the points) and one transparent object under the lamp, plus a line of floor points
through what it refracts. Usage: python3 scripts/refraction_scenes.py"""
import json
import math
import os

OUT = os.path.join(os.path.dirname(__file__), "..", "data", "refraction")
W, H, D = 556.0, 548.8, 559.2  # the Cornell box's room


def normal(poly):
    n = [0.0, 0.0, 0.0]
    for i, a in enumerate(poly):
        b = poly[(i + 1) % len(poly)]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return n


def facing_out(poly, centre):
    """The polygon ordered counter-clockwise seen from outside (away from `centre`)."""
    n = normal(poly)
    c = [sum(p[k] for p in poly) / len(poly) for k in range(3)]
    outward = sum(n[k] * (c[k] - centre[k]) for k in range(3))
    return poly if outward > 0 else poly[::-1]


def room(materials, objects):
    materials.update({"black": {"reflectance": 0},
                      "lamp": {"reflectance": 0, "emission": [53.4071, 37.6991, 12.5664]}})
    lx, lz = (213.0, 343.0), (227.0, 332.0)
    objects += [
        {"name": "floor", "material": "black",
         "polygons": [[[0, 0, 0], [0, 0, D], [W, 0, D], [W, 0, 0]]]},
        {"name": "ceiling", "material": "black",
         "polygons": [[[0, H, 0], [W, H, 0], [W, H, D], [0, H, D]]]},
        {"name": "lamp", "material": "lamp",
         "polygons": [[[lx[0], H - 0.1, lz[0]], [lx[1], H - 0.1, lz[0]], [lx[1], H - 0.1, lz[1]],
                       [lx[0], H - 0.1, lz[1]]]]},
    ]


def box(lo, hi):
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    c = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
    faces = [[[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
             [[x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1]],
             [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0]],
             [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
             [[x0, y0, z0], [x0, y1, z0], [x0, y1, z1], [x0, y0, z1]],
             [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]]]
    return [facing_out(f, c) for f in faces]


def prism(triangle, height):
    c = [sum(p[0] for p in triangle) / 3, height / 2, sum(p[1] for p in triangle) / 3]
    faces = [[[x, 0, z] for x, z in triangle], [[x, height, z] for x, z in triangle]]
    for i in range(3):
        (a, b), (p, q) = triangle[i], triangle[(i + 1) % 3]
        faces.append([[a, 0, b], [p, 0, q], [p, height, q], [a, height, b]])
    return [facing_out(f, c) for f in faces]


def pool(x0, x1, z0, z1, depth, ripple, cells):
    """Water from the floor up to a surface at `depth`, flat or rippled (a height field of
    cells x cells squares, each two triangles), with four walls following its edges."""
    def y(x, z):
        u, v = (x - x0) / (x1 - x0), (z - z0) / (z1 - z0)
        return depth + ripple * math.sin(2 * math.pi * 1.5 * u) * math.sin(2 * math.pi * 1.25 * v)
    n = cells if ripple else 1
    xs = [x0 + (x1 - x0) * i / n for i in range(n + 1)]
    zs = [z0 + (z1 - z0) * j / n for j in range(n + 1)]
    c = [(x0 + x1) / 2, depth / 2, (z0 + z1) / 2]
    faces = []
    for i in range(n):
        for j in range(n):
            a = [xs[i], y(xs[i], zs[j]), zs[j]]
            b = [xs[i + 1], y(xs[i + 1], zs[j]), zs[j]]
            cc = [xs[i + 1], y(xs[i + 1], zs[j + 1]), zs[j + 1]]
            d = [xs[i], y(xs[i], zs[j + 1]), zs[j + 1]]
            if ripple:
                faces += [facing_out([a, b, cc], [c[0], -1e4, c[2]]),
                          facing_out([a, cc, d], [c[0], -1e4, c[2]])]
            else:
                faces.append(facing_out([a, b, cc, d], c))
    faces.append(facing_out([[x0, 0, z0], [x1, 0, z0], [x1, 0, z1], [x0, 0, z1]], c))
    # Walls: the floor edge, then the surface's edge back.
    for edge in ([(x, z0) for x in xs], [(x, z1) for x in xs], [(x0, z) for z in zs],
                 [(x1, z) for z in zs]):
        wall = [[edge[0][0], 0, edge[0][1]], [edge[-1][0], 0, edge[-1][1]]]
        wall += [[x, y(x, z), z] for x, z in reversed(edge)]
        faces.append(facing_out(wall, c))
    return faces


def write(name, glass, polygons, points_z, note):
    materials, objects = {}, []
    room(materials, objects)
    materials["glass"] = glass
    objects.append({"name": name, "material": "glass", "polygons": polygons})
    scene = {"refraction_depth": 2, "materials": materials, "objects": objects,
             "camera": {"eye": [278, 273, -800], "look_at": [278, 100, 280], "fov_deg": 39.3,
                        "width": 256, "height": 256}}
    with open(os.path.join(OUT, name + ".json"), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")
    with open(os.path.join(OUT, name + "-points.csv"), "w") as f:
        f.write("x,y,z,nx,ny,nz\n")
        for i in range(27):
            f.write(f"{20 + 20 * i},0,{points_z},0,1,0\n")


os.makedirs(OUT, exist_ok=True)
write("block", {"ior": 1.5}, box([198, 0, 200], [358, 160, 360]), 280,
      "a glass block on the floor under the lamp")
write("prism", {"ior": [1.56, 1.6, 1.68]}, prism([(218, 220), (338, 220), (278, 324)], 120), 262,
      "a dispersive prism")
write("pane", {"ior": 1.5}, box([1, 250, 1], [555, 270, 558]), 280,
      "a wide glass pane, 20 thick, across the room between the lamp and the floor (issue 37)")
write("water-flat", {"ior": 1.33}, pool(100, 456, 100, 460, 100, 0, 1), 280, "a flat pool")
write("water-rippled", {"ior": 1.33}, pool(100, 456, 100, 460, 100, 8, 6), 280,
      "a rippled pool (000 Fig. 6)")
