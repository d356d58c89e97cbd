#!/usr/bin/env python3
"""Specular transfer in the global solution (issue 37): the scenes, the probe points and the
error tables of bench/specular_solution.sh.

  specular_solution.py scenes DIR            writes DIR/cornell-glass-pane.json,
                                             DIR/cornell-mirror-light.json,
                                             DIR/glossy-ring-{white,black}.json, DIR/points.csv
  specular_solution.py table REF MODEL RUN...   prints the RMS errors of each run
                                             (LABEL=CSV: E plus refracted and glossy) against
                                             the path tracer's REF (and MODEL, or - for none),
                                             per group of points (of points.csv; other points
                                             as one group)

Both scenes are the Cornell box of data/cornell-box/:
- cornell-glass-pane: a horizontal pane of glass (index 1.5, no Fresnel, 8 units thick,
  240 x 240) hanging 100 under the lamp, a window between the lamp and the room;
- cornell-mirror-light: the lamp switched off (a white ceiling), a point light in the middle of
  the room, and a mirror (specular 0.9) on the back wall, 150 x 300, between the points there.
The points see the room's indirect light: the ceiling, the back wall, the floor away from the
objects and both side walls (1 unit in front of them). And the glossy ring of data/glossy-ring/
on its white floor and on a black one (its floor points: data/glossy-ring/ring-points.csv).
"""
import csv
import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GROUPS = ("ceiling", "back wall", "floor", "side walls")


def left_wall_x(y, z):
    """The Cornell box's left wall, bilinear between its corners (it leans and is not planar)."""
    s, t = z / 559.2, y / 548.8
    return (1 - t) * (552.8 - 3.2 * s) + t * 556


def points():
    rows = []
    for x in (60, 180, 380, 500):
        for z in (80, 480):
            rows.append(("ceiling", x, 548.8, z, 0, -1, 0))
    for x in (60, 200, 400, 520):
        for y in (60, 250, 450):
            rows.append(("back wall", x, y, 559.2, 0, 0, -1))
    for x, z in ((40, 40), (40, 330), (200, 320), (500, 60), (520, 300), (180, 20), (300, 200),
                 (350, 230)):
        rows.append(("floor", x, 0, z, 0, 1, 0))
    for y in (100, 300, 480):
        for z in (100, 400):
            rows.append(("side walls", 1, y, z, 1, 0, 0))
            rows.append(("side walls", round(left_wall_x(y, z) - 1, 3), y, z, -1, 0, 0))
    return rows


def box(x0, x1, y0, y1, z0, z1):
    """The six faces of a box, fronts facing out."""
    c = lambda i: [(x0, x1)[i & 1], (y0, y1)[(i >> 1) & 1], (z0, z1)[(i >> 2) & 1]]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return [[c(i) for i in q] for q in quads]


def cornell_box():
    return json.loads((ROOT / "data/cornell-box/scene.json").read_text())


def scenes(out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    pane = cornell_box()
    pane["materials"]["glass"] = {"ior": 1.5, "reflectance": 0}
    pane["objects"].append({"name": "pane", "material": "glass",
                            "polygons": box(158, 398, 440, 448, 160, 400)})
    (out / "cornell-glass-pane.json").write_text(json.dumps(pane, indent=1))

    mirror = cornell_box()
    mirror["materials"]["light"] = dict(mirror["materials"]["white"])  # the lamp off
    mirror["materials"]["mirror"] = {"reflectance": 0.05, "specular": 0.9}
    # facing -z, into the room, 1 unit in front of the back wall
    mirror["objects"].append({"name": "mirror", "material": "mirror", "polygons": [
        [[230, 120, 558.2], [230, 420, 558.2], [380, 420, 558.2], [380, 120, 558.2]]]})
    mirror["lights"] = [{"position": [278, 330, 250], "intensity": [60000, 45000, 20000]}]
    (out / "cornell-mirror-light.json").write_text(json.dumps(mirror, indent=1))

    for floor, reflectance in (("white", None), ("black", [0, 0, 0])):
        ring = json.loads((ROOT / "data/glossy-ring/scene.json").read_text())
        for o in ring["objects"]:
            if "mesh" in o:
                o["mesh"] = str(ROOT / "data/glossy-ring" / o["mesh"])
        if reflectance:
            ring["materials"]["floor"]["reflectance"] = reflectance
        (out / f"glossy-ring-{floor}.json").write_text(json.dumps(ring, indent=1))

    with open(out / "points.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x", "y", "z", "nx", "ny", "nz"])
        for row in points():
            w.writerow(row[1:])


def values(path):
    rows = list(csv.DictReader(open(path)))
    return [[float(r["E_" + c]) + float(r.get("refracted_" + c) or 0) +
             float(r.get("glossy_" + c) or 0) for c in "rgb"] for r in rows]


def rms(rows, ref, group):
    idx = [i for i, p in enumerate(points()) if p[0] == group] if group else range(len(ref))
    errors = [rows[i][c] - ref[i][c] for i in idx for c in range(3)]
    mean = sum(ref[i][c] for i in idx for c in range(3)) / len(errors)
    return 100 * math.sqrt(sum(e * e for e in errors) / len(errors)) / mean


def table(reference, model, runs):
    ref = values(reference)
    ref_model = values(model) if model != "-" else None
    groups = GROUPS if len(ref) == len(points()) else ()
    extra = " all points vs the model |" if ref_model else ""
    print("| solution | " + "".join(g + " | " for g in groups) + "all points |" + extra)
    print("|---|" + "---|" * (len(groups) + 1 + (1 if ref_model else 0)))
    for run in runs:
        label, path = run.split("=", 1)
        rows = values(path)
        cells = [f"{rms(rows, ref, g):.2f}" for g in groups] + [f"{rms(rows, ref, None):.2f}"]
        if ref_model:
            cells.append(f"{rms(rows, ref_model, None):.2f}")
        print(f"| {label} | " + " | ".join(cells) + " |")
    se = [float(r["se_" + c]) / max(float(r["E_" + c]), 1e-300)
          for r in csv.DictReader(open(reference)) for c in "rgb"]
    print()
    print(f"The reference's relative standard error: at most {100 * max(se):.2f}% a point and "
          f"channel, {100 * math.sqrt(sum(s * s for s in se) / len(se)):.2f}% RMS.")


if __name__ == "__main__":
    if sys.argv[1:2] == ["scenes"] and len(sys.argv) == 3:
        scenes(sys.argv[2])
    elif sys.argv[1:2] == ["table"] and len(sys.argv) >= 5:
        table(sys.argv[2], sys.argv[3], sys.argv[4:])
    else:
        sys.exit(__doc__)
