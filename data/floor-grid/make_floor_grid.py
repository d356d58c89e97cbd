#!/usr/bin/env python3
"""Writes a floor of N x N squares, each cut in two triangles (2 N^2 triangles, an OBJ), under
one square lamp, as a scene: the case of a user's finely tessellated mesh that sees nothing but
its light (a floor's triangles are coplanar: they see neither each other nor themselves).

    python3 make_floor_grid.py [--cells 100] [-o scene.json]

Metres; y is up; the floor spans [0, 10] x [0, 10] in x and z, the lamp 1 m square at 3 m.
The mesh is written beside the scene as floor-N.obj. The same arguments write the same bytes."""
import argparse
import json
import os


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=100, help="squares along each side")
    parser.add_argument("-o", "--output", default="scene.json", help="scene file to write")
    args = parser.parse_args()
    n, size = args.cells, 10.0
    folder = os.path.dirname(os.path.abspath(args.output))
    os.makedirs(folder, exist_ok=True)
    mesh = f"floor-{n}.obj"
    with open(os.path.join(folder, mesh), "w") as out:
        out.write(f"# {n} x {n} squares, two triangles each, facing +y\n")
        for i in range(n + 1):
            for j in range(n + 1):
                out.write(f"v {size * i / n:.6f} 0 {size * j / n:.6f}\n")
        for i in range(n):
            for j in range(n):
                a = i * (n + 1) + j + 1  # OBJ counts from 1
                b, c, d = a + (n + 1), a + (n + 1) + 1, a + 1
                # Counter-clockwise seen from +y: a (x, z), d (x, z + 1), c, b.
                out.write(f"f {a} {d} {c}\nf {a} {c} {b}\n")
    scene = {
        "materials": {
            "floor": {"reflectance": [0.6, 0.6, 0.6]},
            "lamp": {"reflectance": 0, "emission": [50, 50, 50]},
        },
        "objects": [
            {"name": "floor", "mesh": mesh, "material": "floor"},
            {"name": "lamp", "material": "lamp",
             "polygons": [[[4.5, 3, 4.5], [5.5, 3, 4.5], [5.5, 3, 5.5], [4.5, 3, 5.5]]]},
        ],
        "camera": {"eye": [5, 6, -6], "look_at": [5, 0, 5], "up": [0, 1, 0], "fov_deg": 60,
                   "width": 256, "height": 192},
    }
    with open(args.output, "w") as out:
        json.dump(scene, out, indent=1)
        out.write("\n")


if __name__ == "__main__":
    main()
