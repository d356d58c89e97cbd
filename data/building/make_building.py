#!/usr/bin/env python3
"""Writes a procedural office building as a scene (issue 21): storeys of rooms on a grid, walls
with thickness, a door in every wall between two rooms, windows in the outer walls as area
sources (daylight), a ceiling panel in each room without a window, and furniture (tables with
chairs, bookcases full of books, cabinets, sofas) placed at random from a seed.

    python3 make_building.py [--storeys 3] [--rooms-x 5] [--rooms-z 5] [--seed 1] [-o scene.json]

Metres; y is up. The defaults give about 30,000 polygons; the polygon count grows with the
rooms (about 400 a room). The same arguments write the same bytes. No two polygons overlap or
interpenetrate: furniture stands on the floor and against the walls, clear of the doors."""
import argparse
import json
import random
import sys

ROOM_X, ROOM_Z = 4.0, 5.0  # a room's cell on the grid, wall centre to wall centre
STOREY = 3.0               # floor to floor
SLAB = 0.25                # floor slab: a room's ceiling is STOREY - SLAB above its floor
WALL = 0.15                # wall thickness
DOOR_W, DOOR_H = 0.9, 2.1
WINDOW = (0.9, 2.2)        # sill and head heights; windows span the middle of the outer wall


def rect(axis, value, lo, hi, normal_sign):
    """Axis-aligned rectangle in the plane coordinate[axis] = value, lo/hi bounding the other two
    coordinates in increasing axis order ((y, z), (x, z) or (x, y)); counter-clockwise seen from
    the side its normal (normal_sign times the axis) points to."""
    u, v = [i for i in range(3) if i != axis]

    def p(a, b):
        q = [0.0] * 3
        q[axis], q[u], q[v] = round(value, 6), round(a, 6), round(b, 6)
        return q
    corners = [p(lo[0], lo[1]), p(hi[0], lo[1]), p(hi[0], hi[1]), p(lo[0], hi[1])]
    # Counter-clockwise in (u, v) faces along u x v: +x for axis x (y, z), -y for axis y
    # (x, z), +z for axis z (x, y).
    along_u_cross_v = 1 if axis != 1 else -1
    return corners if normal_sign == along_u_cross_v else corners[::-1]


def box(x0, x1, y0, y1, z0, z1, skip=()):
    """A box's faces, fronts outward; `skip` leaves faces out (-x, +x, -y, +y, -z, +z)."""
    faces = {
        '-x': rect(0, x0, (y0, z0), (y1, z1), -1), '+x': rect(0, x1, (y0, z0), (y1, z1), 1),
        '-y': rect(1, y0, (x0, z0), (x1, z1), -1), '+y': rect(1, y1, (x0, z0), (x1, z1), 1),
        '-z': rect(2, z0, (x0, y0), (x1, y1), -1), '+z': rect(2, z1, (x0, y0), (x1, y1), 1),
    }
    return [f for k, f in faces.items() if k not in skip]


def wall_with_hole(axis, value, lo, hi, hole, normal_sign):
    """The rectangle lo..hi (coordinates (a, b) in the wall's plane) less the rectangle `hole`
    (a0, a1, b0, b1): up to four rectangles that do not overlap."""
    (a_lo, b_lo), (a_hi, b_hi) = lo, hi
    a0, a1, b0, b1 = hole
    pieces = [((a_lo, b_lo), (a0, b_hi)), ((a1, b_lo), (a_hi, b_hi)),
              ((a0, b_lo), (a1, b0)), ((a0, b1), (a1, b_hi))]
    return [rect(axis, value, p, q, normal_sign) for p, q in pieces
            if q[0] - p[0] > 1e-9 and q[1] - p[1] > 1e-9]


class Building:
    def __init__(self, storeys, rooms_x, rooms_z, seed):
        self.storeys, self.nx, self.nz = storeys, rooms_x, rooms_z
        self.random = random.Random(seed)
        self.objects = []

    def add(self, name, material, polygons):
        if polygons:
            self.objects.append({"name": name, "material": material, "polygons": polygons})

    def room(self, s, i, j):
        """Room (storey s, column i along x, row j along z): its shell, openings and furniture."""
        name = f"storey {s} room {i},{j}"
        h = WALL / 2
        x0, x1 = i * ROOM_X + h, (i + 1) * ROOM_X - h
        z0, z1 = j * ROOM_Z + h, (j + 1) * ROOM_Z - h
        y0 = s * STOREY
        y1 = y0 + STOREY - SLAB
        self.add(f"{name} floor", "oak", [rect(1, y0, (x0, z0), (x1, z1), 1)])
        ceiling = [rect(1, y1, (x0, z0), (x1, z1), -1)]
        windows = []
        # Walls: -x and +x run along z; -z and +z along x. A door where a neighbour is, a window
        # where the wall is outside. (a, b) are the wall's in-plane coordinates in axis order.
        sides = [
            ('-x', 0, x0, (z0, y0), (z1, y1), 1, i > 0, i == 0),
            ('+x', 0, x1, (z0, y0), (z1, y1), -1, i < self.nx - 1, i == self.nx - 1),
            ('-z', 2, z0, (x0, y0), (x1, y1), 1, j > 0, j == 0),
            ('+z', 2, z1, (x0, y0), (x1, y1), -1, j < self.nz - 1, j == self.nz - 1),
        ]
        walls, jambs = [], []
        for side, axis, value, lo, hi, sign, door, outside in sides:
            # In-plane coordinates: for axis x they are (y, z) in rect's order; keep (along, up).
            along_lo, along_hi = lo[0], hi[0]
            mid = (along_lo + along_hi) / 2
            if door:
                hole = (mid - DOOR_W / 2, mid + DOOR_W / 2, y0, y0 + DOOR_H)
            elif outside:
                width = 0.45 * (along_hi - along_lo)
                hole = (mid - width / 2, mid + width / 2, y0 + WINDOW[0], y0 + WINDOW[1])
            else:
                hole = None
            walls += self.wall(axis, value, (along_lo, y0), (along_hi, y1), hole, sign)
            if outside and hole:
                windows.append(self.plane(axis, value, hole, sign))
            if door and side in ('+x', '+z'):
                # The door's reveal through the wall's thickness, to the next room: two jambs
                # and the lintel's underside (the floor's threshold is left open: no light
                # reaches the slab's edge through a 2 mm gap, and none leaks there).
                jambs += self.reveal(axis, value, value + WALL, hole)
        self.add(f"{name} walls", "plaster", walls)
        if jambs:
            self.add(f"{name} door reveals", "plaster", jambs)
        if windows:
            self.add(f"{name} windows", "sky", windows)
        else:
            # No window: a ceiling panel lights the room.
            cx, cz = (x0 + x1) / 2, (z0 + z1) / 2
            panel = (cx - 0.4, cx + 0.4, cz - 0.4, cz + 0.4)
            ceiling = wall_with_hole(1, y1, (x0, z0), (x1, z1), panel, -1)
            self.add(f"{name} ceiling panel", "panel",
                     [rect(1, y1, (panel[0], panel[2]), (panel[1], panel[3]), -1)])
        self.add(f"{name} ceiling", "plaster", ceiling)
        self.furnish(name, x0, x1, y0, z0, z1)

    @staticmethod
    def wall(axis, value, lo, hi, hole, sign):
        """A wall along x or z, in rect's coordinate order ((y, z) for axis x, (x, y) for z)."""
        if axis == 0:
            (a0, y0), (a1, y1) = lo, hi
            if hole is None:
                return [rect(0, value, (y0, a0), (y1, a1), sign)]
            return wall_with_hole(0, value, (y0, a0), (y1, a1), (hole[2], hole[3], hole[0], hole[1]),
                                  sign)
        if hole is None:
            return [rect(2, value, lo, hi, sign)]
        return wall_with_hole(2, value, lo, hi, hole, sign)

    @staticmethod
    def plane(axis, value, hole, sign):
        a0, a1, b0, b1 = hole
        if axis == 0:
            return rect(0, value, (b0, a0), (b1, a1), sign)
        return rect(2, value, (a0, b0), (a1, b1), sign)

    @staticmethod
    def reveal(axis, v0, v1, hole):
        """The faces inside a door opening between wall planes v0 < v1 on `axis`."""
        a0, a1, b0, b1 = hole
        if axis == 0:  # door in a wall normal to x: jambs normal to z, lintel normal to y
            return [rect(2, a0, (v0, b0), (v1, b1), 1), rect(2, a1, (v0, b0), (v1, b1), -1),
                    rect(1, b1, (v0, a0), (v1, a1), -1)]
        return [rect(0, a0, (b0, v0), (b1, v1), 1), rect(0, a1, (b0, v0), (b1, v1), -1),
                rect(1, b1, (a0, v0), (a1, v1), -1)]

    def furnish(self, name, x0, x1, y0, z0, z1):
        r = self.random
        cx, cz = (x0 + x1) / 2, (z0 + z1) / 2
        # A table in the middle with chairs round it.
        tw, td = r.uniform(1.2, 1.8), r.uniform(0.8, 1.0)
        top = 0.75
        table = box(cx - tw / 2, cx + tw / 2, y0 + top - 0.04, y0 + top, cz - td / 2, cz + td / 2)
        for lx in (cx - tw / 2 + 0.05, cx + tw / 2 - 0.1):
            for lz in (cz - td / 2 + 0.05, cz + td / 2 - 0.1):
                table += box(lx, lx + 0.05, y0, y0 + top - 0.04, lz, lz + 0.05, skip=('-y', '+y'))
        self.add(f"{name} table", "walnut", table)
        chairs = []
        for k in range(r.randint(2, 6)):
            side = k % 2  # -z or +z of the table
            along = cx - tw / 2 + (k // 2 + 0.5) * tw / 3 - 0.22
            cz0 = cz - td / 2 - 0.55 if side == 0 else cz + td / 2 + 0.1
            chairs += self.chair(along, cz0, y0, back_at_low_z=(side == 0))
        self.add(f"{name} chairs", "beech", chairs)
        # Corners (clear of the doors, which are mid-wall): a bookcase, a cabinet, a sofa.
        corners = [(x0, z0, 1, 1), (x1, z0, -1, 1), (x0, z1, 1, -1), (x1, z1, -1, -1)]
        r.shuffle(corners)
        kinds = ["bookcase", "cabinet", "sofa", "bookcase"]
        for (ax, az, sx, sz), kind in zip(corners, kinds[:r.randint(2, 4)]):
            if kind == "bookcase":
                self.bookcase(name, ax, az, sx, sz, y0)
            elif kind == "cabinet":
                w, d, hgt = r.uniform(0.8, 1.2), 0.5, r.uniform(0.7, 1.0)
                self.add(f"{name} cabinet", "white lacquer",
                         box(*span(ax, sx, w), y0, y0 + hgt, *span(az, sz, d), skip=('-y',)))
            else:
                self.sofa(name, ax, az, sx, sz, y0)

    @staticmethod
    def chair(x, z, y0, back_at_low_z):
        seat, w = 0.45, 0.44
        faces = box(x, x + w, y0 + seat - 0.04, y0 + seat, z, z + w)
        for lx in (x, x + w - 0.04):
            for lz in (z, z + w - 0.04):
                faces += box(lx, lx + 0.04, y0, y0 + seat - 0.04, lz, lz + 0.04, skip=('-y', '+y'))
        bz = z if back_at_low_z else z + w - 0.04
        faces += box(x, x + w, y0 + seat, y0 + 0.9, bz, bz + 0.04, skip=('-y',))
        return faces

    def bookcase(self, name, ax, az, sx, sz, y0):
        """A bookcase against the x wall of a corner: sides, shelves and rows of books."""
        r = self.random
        w, d, hgt = r.uniform(0.9, 1.4), 0.35, 2.0
        xa, xb = span(ax, sx, d)
        za, zb = span(az, sz, w)
        shelves = 4
        frame = box(xa, xb, y0, y0 + hgt, za, za + 0.03, skip=('-y',))
        frame += box(xa, xb, y0, y0 + hgt, zb - 0.03, zb, skip=('-y',))
        books = []
        for k in range(shelves):
            sy = y0 + k * hgt / shelves
            frame += box(xa, xb, sy, sy + 0.02, za + 0.03, zb - 0.03, skip=('-y',) if k == 0 else ())
            z = za + 0.04
            while True:
                t = r.uniform(0.04, 0.09)
                if z + t > zb - 0.04:
                    break
                bh = r.uniform(0.18, min(0.3, hgt / shelves - 0.06))
                bd = r.uniform(0.18, d - 0.04)
                bx = (xa, xa + bd) if sx > 0 else (xb - bd, xb)
                books += box(bx[0], bx[1], sy + 0.02, sy + 0.02 + bh, z, z + t, skip=('-y',))
                z += t + 0.003
        frame += box(xa, xb, y0 + hgt - 0.02, y0 + hgt, za + 0.03, zb - 0.03)
        self.add(f"{name} bookcase", "walnut", frame)
        self.add(f"{name} books", r.choice(["red cloth", "blue cloth", "paper"]), books)

    def sofa(self, name, ax, az, sx, sz, y0):
        w, d = self.random.uniform(1.6, 2.0), 0.85
        xa, xb = span(ax, sx, w)
        za, zb = span(az, sz, d)
        back = (za, za + 0.2) if sz > 0 else (zb - 0.2, zb)
        seat_z = (back[1], zb) if sz > 0 else (za, back[0])
        faces = box(xa + 0.2, xb - 0.2, y0, y0 + 0.42, *seat_z, skip=('-y',))
        faces += box(xa, xb, y0, y0 + 0.85, *back, skip=('-y',))
        for arm in ((xa, xa + 0.2), (xb - 0.2, xb)):
            faces += box(*arm, y0, y0 + 0.6, *seat_z, skip=('-y',))
        self.add(f"{name} sofa", "fabric", faces)


def span(corner, sign, size):
    """The interval of length `size` from a wall at `corner` into the room (sign: +1 or -1),
    1 mm off the wall: furniture does not share the wall's plane."""
    a = corner + sign * 0.001
    b = a + sign * size
    return (min(a, b), max(a, b))


MATERIALS = {
    "oak": {"reflectance": [0.45, 0.33, 0.22]},
    "plaster": {"reflectance": [0.78, 0.76, 0.72]},
    "walnut": {"reflectance": [0.30, 0.20, 0.13]},
    "beech": {"reflectance": [0.60, 0.45, 0.30]},
    "white lacquer": {"reflectance": [0.80, 0.80, 0.78]},
    "fabric": {"reflectance": [0.25, 0.30, 0.45]},
    "red cloth": {"reflectance": [0.55, 0.10, 0.08]},
    "blue cloth": {"reflectance": [0.10, 0.18, 0.50]},
    "paper": {"reflectance": [0.75, 0.72, 0.62]},
    # Overcast daylight through the openings, W/m^2; the opening reflects nothing.
    "sky": {"reflectance": [0, 0, 0], "emission": [80, 90, 100]},
    "panel": {"reflectance": [0.8, 0.8, 0.8], "emission": [120, 110, 95]},
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--storeys", type=int, default=3)
    parser.add_argument("--rooms-x", type=int, default=5, help="rooms along x on each storey")
    parser.add_argument("--rooms-z", type=int, default=5, help="rooms along z on each storey")
    parser.add_argument("--seed", type=int, default=1, help="the furniture's seed")
    parser.add_argument("-o", "--output", default="-", help="scene file (default: stdout)")
    a = parser.parse_args()
    if min(a.storeys, a.rooms_x, a.rooms_z) < 1:
        parser.error("--storeys, --rooms-x and --rooms-z must be at least 1")
    b = Building(a.storeys, a.rooms_x, a.rooms_z, a.seed)
    for s in range(a.storeys):
        for j in range(a.rooms_z):
            for i in range(a.rooms_x):
                b.room(s, i, j)
    # The camera stands in the ground floor's corner room, looking through its door along x.
    camera = {"eye": [0.6, 1.6, 0.8], "look_at": [ROOM_X + 2.0, 1.0, ROOM_Z / 2],
              "up": [0, 1, 0], "fov_deg": 70, "width": 480, "height": 360}
    scene = {"materials": MATERIALS, "objects": b.objects, "camera": camera}
    text = json.dumps(scene, separators=(",", ":")) + "\n"
    polygons = sum(len(o["polygons"]) for o in b.objects)
    print(f"make_building: {a.storeys} storeys of {a.rooms_x} x {a.rooms_z} rooms, "
          f"{polygons} polygons", file=sys.stderr)
    if a.output == "-":
        sys.stdout.write(text)
    else:
        with open(a.output, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
