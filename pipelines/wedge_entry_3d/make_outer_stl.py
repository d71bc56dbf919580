"""Writes wedge_outer.stl: the wetted outside of wedge.geo (two bottom faces, the deck and the two
end caps) as a binary STL with outward normals, about 0.04 m along the wedge and 24 segments
across every edge of the section (matching, so the surface is closed). Run: python3 make_outer_stl.py"""
import math
import struct

DEADRISE, HALF_BREADTH, LENGTH, KEEL_Z = math.radians(25), 0.47, 1.5, 0.85
ALONG, ACROSS = 0.04, 24
CHINE = HALF_BREADTH * math.tan(DEADRISE)


def sub(a, b): return [a[i] - b[i] for i in range(3)]
def add(a, b): return [a[i] + b[i] for i in range(3)]
def mul(a, s): return [a[i] * s for i in range(3)]
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))


CENTRE = [0.0, 0.0, KEEL_Z + 2 * CHINE / 3]
triangles = []


def triangle(a, b, c):
    n = cross(sub(b, a), sub(c, a))
    if dot(n, sub(mul(add(add(a, b), c), 1 / 3), CENTRE)) < 0:
        b, c = c, b
    triangles.append((a, b, c))


def grid(origin, u, v, nu, nv):
    point = lambda i, j: add(add(origin, mul(u, i / nu)), mul(v, j / nv))
    for i in range(nu):
        for j in range(nv):
            triangle(point(i, j), point(i + 1, j), point(i + 1, j + 1))
            triangle(point(i, j), point(i + 1, j + 1), point(i, j + 1))


n_along = math.ceil(LENGTH / ALONG)
keel = [0.0, -LENGTH / 2, KEEL_Z]
right, left = [HALF_BREADTH, -LENGTH / 2, KEEL_Z + CHINE], [-HALF_BREADTH, -LENGTH / 2, KEEL_Z + CHINE]
along = [0.0, LENGTH, 0.0]
grid(keel, sub(right, keel), along, ACROSS, n_along)
grid(keel, sub(left, keel), along, ACROSS, n_along)
grid(left, sub(right, left), along, ACROSS, n_along)
for y in (-LENGTH / 2, LENGTH / 2):
    a, b, c = [0.0, y, KEEL_Z], [HALF_BREADTH, y, KEEL_Z + CHINE], [-HALF_BREADTH, y, KEEL_Z + CHINE]
    q = lambda i, j: add(add(a, mul(sub(b, a), i / ACROSS)), mul(sub(c, a), j / ACROSS))
    for i in range(ACROSS):
        for j in range(ACROSS - i):
            triangle(q(i, j), q(i + 1, j), q(i, j + 1))
            if i + j <= ACROSS - 2:
                triangle(q(i + 1, j), q(i + 1, j + 1), q(i, j + 1))

with open("wedge_outer.stl", "wb") as f:
    f.write(b"hydromodal wedge_entry_3d outer surface".ljust(80, b" "))
    f.write(struct.pack("<I", len(triangles)))
    for a, b, c in triangles:
        n = cross(sub(b, a), sub(c, a))
        length = math.sqrt(dot(n, n))
        f.write(struct.pack("<12fH", *[x / length for x in n], *a, *b, *c, 0))
print(f"wedge_outer.stl: {len(triangles)} triangles")
