#!/usr/bin/env python3
"""A scene from a model nobody here wrote (issue 36, target 4): the OBJ and MTL that Assimp
exports from an IFC building model (`assimp export model.ifc model.obj -tri`), split into one
mesh per material, with the materials' diffuse colours as reflectances, a sky of emitting quads
round it, a ground and a camera from the model's bounds.

The scene loader reads one material per mesh (OBJ `usemtl` is issue 39's), so each material's
triangles go to a mesh of their own. What the scene does not model is said, not hidden:
- every surface is Lambertian: `Kd` becomes the reflectance (at most 0.9); `Ks` (gloss) is
  dropped;
- glass (`d` < 1) is opaque with its own dark `Kd`, as windows look from outside by day;
- triangles of zero area (to 1e-12 of the model's size squared) are left out and counted;
- a material defined twice under one name (Assimp writes one per IFC style) takes its first.

Usage: ifc_house.py MODEL.obj OUT_DIR   (writes OUT_DIR/scene.json and OUT_DIR/meshes/*.obj)
"""
import json
import math
import os
import re
import sys
import unicodedata


def read_mtl(path):
    materials, name = {}, None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "newmtl":
                name = line.strip()[len("newmtl"):].strip()
                if name in materials:
                    name = None  # a second definition: the first one stands
                else:
                    materials[name] = {"Kd": [0.6, 0.6, 0.6], "d": 1.0}
            elif name is not None and words[0] == "Kd":
                materials[name]["Kd"] = [float(v) for v in words[1:4]]
            elif name is not None and words[0] == "d":
                materials[name]["d"] = float(words[1])
    return materials


def read_obj(path):
    """Vertices and, per material, triangles (vertex indices, 0-based)."""
    vertices, by_material, material, mtllib = [], {}, "<none>", None
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(v) for v in line.split()[1:4]])
            elif line.startswith("f "):
                corners = [int(w.split("/")[0]) - 1 for w in line.split()[1:]]
                for i in range(1, len(corners) - 1):  # a fan, should a polygon remain
                    by_material.setdefault(material, []).append(
                        (corners[0], corners[i], corners[i + 1]))
            elif line.startswith("usemtl"):
                material = line.strip()[len("usemtl"):].strip()
            elif line.startswith("mtllib"):
                mtllib = line.strip()[len("mtllib"):].strip()
    return vertices, by_material, mtllib


def area(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    return 0.5 * math.sqrt(sum(x * x for x in n))


def slug(name, used):
    ascii = unicodedata.normalize("NFKD", name).encode("ascii", "ignore").decode()  # ä: a
    base = re.sub(r"[^a-z0-9]+", "-", ascii.lower()).strip("-")
    base = base or "material"
    out, k = base, 2
    while out in used:
        out, k = f"{base}-{k}", k + 1
    used.add(out)
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    obj_path, out_dir = sys.argv[1], sys.argv[2]
    vertices, by_material, mtllib = read_obj(obj_path)
    if not vertices:
        sys.exit(f"ifc_house: {obj_path}: no vertices")
    mtl = read_mtl(os.path.join(os.path.dirname(obj_path), mtllib)) if mtllib else {}
    lo = [min(v[i] for v in vertices) for i in range(3)]
    hi = [max(v[i] for v in vertices) for i in range(3)]
    size = max(hi[i] - lo[i] for i in range(3))
    os.makedirs(os.path.join(out_dir, "meshes"), exist_ok=True)

    scene = {"materials": {}, "objects": []}
    used, dropped, kept = set(), 0, 0
    for name in sorted(by_material):
        m = mtl.get(name, {"Kd": [0.6, 0.6, 0.6], "d": 1.0})
        key = slug(name, used)
        triangles = []
        for t in by_material[name]:
            if area(*(vertices[i] for i in t)) <= 1e-12 * size * size:
                dropped += 1
            else:
                triangles.append(t)
        if not triangles:
            continue
        kept += len(triangles)
        # The mesh holds the vertices its triangles use, renumbered.
        index = {}
        lines = [f"# {name} ({len(triangles)} triangles)"]
        faces = []
        for t in triangles:
            for i in t:
                if i not in index:
                    index[i] = len(index) + 1
                    v = vertices[i]
                    lines.append(f"v {v[0]!r} {v[1]!r} {v[2]!r}")
            faces.append("f " + " ".join(str(index[i]) for i in t))
        with open(os.path.join(out_dir, "meshes", key + ".obj"), "w") as f:
            f.write("\n".join(lines + faces) + "\n")
        scene["materials"][key] = {"reflectance": [round(min(0.9, max(0.0, c)), 4)
                                                   for c in m["Kd"]]}
        scene["objects"].append({"name": name, "mesh": f"meshes/{key}.obj", "material": key})

    # The ground (a grey meadow) 2 cm below the model's ground floor (y = 0 where the model has
    # it, else its lowest point): not in the plane of the model's own terrain, whose overlap
    # would be settled by polygon order alone; the sky: five emitting quads facing in, four
    # model sizes away.
    ground = (0.0 if lo[1] < 0.0 < hi[1] else lo[1]) - 0.02
    cx, cz = 0.5 * (lo[0] + hi[0]), 0.5 * (lo[2] + hi[2])
    r, top = 4 * size, ground + 3 * size
    scene["materials"]["ground"] = {"reflectance": [0.3, 0.32, 0.25]}
    scene["materials"]["sky"] = {"reflectance": [0, 0, 0], "emission": [0.8, 0.9, 1.1]}
    g = [[cx - r, ground, cz - r], [cx - r, ground, cz + r], [cx + r, ground, cz + r],
         [cx + r, ground, cz - r]]  # facing up
    scene["objects"].append({"name": "ground", "polygons": [g], "material": "ground"})
    corner = lambda sx, y, sz: [cx + sx * r, y, cz + sz * r]
    sky = [
        [corner(-1, top, -1), corner(1, top, -1), corner(1, top, 1), corner(-1, top, 1)],  # down
        [corner(-1, ground, -1), corner(1, ground, -1), corner(1, top, -1), corner(-1, top, -1)],
        [corner(1, ground, 1), corner(-1, ground, 1), corner(-1, top, 1), corner(1, top, 1)],
        [corner(-1, ground, 1), corner(-1, ground, -1), corner(-1, top, -1), corner(-1, top, 1)],
        [corner(1, ground, -1), corner(1, ground, 1), corner(1, top, 1), corner(1, top, -1)],
    ]
    scene["objects"].append({"name": "sky", "polygons": sky, "material": "sky"})
    # The camera: from the front left, above the eaves, the whole model in view.
    centre = [cx, 0.5 * (lo[1] + hi[1]), cz]
    eye = [centre[0] - 1.0 * size, centre[1] + 0.45 * size, centre[2] - 1.3 * size]
    scene["camera"] = {"eye": [round(v, 3) for v in eye],
                       "look_at": [round(v, 3) for v in centre], "up": [0, 1, 0],
                       "fov_deg": 40, "width": 512, "height": 384}
    with open(os.path.join(out_dir, "scene.json"), "w") as f:
        json.dump(scene, f, indent=1)
    print(f"ifc_house: {kept} triangles in {len(used)} materials, {dropped} of zero area left "
          f"out; model {hi[0] - lo[0]:.2f} x {hi[1] - lo[1]:.2f} x {hi[2] - lo[2]:.2f}; wrote "
          f"{out_dir}/scene.json", file=sys.stderr)


if __name__ == "__main__":
    main()
