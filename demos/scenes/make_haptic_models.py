#!/usr/bin/env python3
"""Writes the models of the default haptic scene (haptic.json) beside this script, in millimetres:
  haptic_hill.unurbs.json  a solid NURBS ellipsoid, semi-axes 420 x 420 x 100: a low hill (the NURBS environment;
                           a solid, so NURBS probes meet it in the NURBS-NURBS routine, not the generic one)
  haptic_plate.obj         a closed bumpy slab, 800 x 800 x ~50, bumps of +-12 (the mesh environment)
  haptic_tool.obj          a closed stylus (a capsule: radius 25, 170 long, along z) (the mesh probe)
Deterministic: rerunning rewrites the same files."""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def hill(a=420.0, b=420.0, c=100.0):
    # The exact rational sphere of ball_r150.unurbs.json (degree 2 x 2, 9 x 5 net), scaled per axis: NURBS are
    # affine invariant, so this is an exact ellipsoid and still closes up.
    w = math.sqrt(0.5)
    ring = [(1, 0, 1), (1, 1, w), (0, 1, 1), (-1, 1, w), (-1, 0, 1), (-1, -1, w), (0, -1, 1), (1, -1, w), (1, 0, 1)]
    meridian = [(0, -1, 1), (1, -1, w), (1, 0, 1), (1, 1, w), (0, 1, 1)]  # (radius factor, z factor, weight)
    net = [[[a * rx * mr, b * ry * mr, c * mz, rw * mw] for (mr, mz, mw) in meridian] for (rx, ry, rw) in ring]
    surface = {"degree_u": 2, "degree_v": 2, "knots_u": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
               "knots_v": [0, 0, 0, 0.5, 0.5, 1, 1, 1], "control_points": net}
    return {"type": "nurbs", "solid": True, "surfaces": [surface]}


def write_obj(path, comment, vertices, triangles):
    with open(path, "w") as f:
        f.write("# " + comment + "\n")
        for v in vertices:
            f.write("v %.6f %.6f %.6f\n" % v)
        for t in triangles:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def bumpy_plate(n=24, size=800.0, bump=12.0, bottom=-40.0):
    # Top and bottom grids share the rim, walls join them: every edge has two triangles (a closed solid).
    def height(x, y):
        return bump * math.cos(2 * math.pi * x / 260.0) * math.cos(2 * math.pi * y / 260.0)

    vertices = []
    for layer in (0, 1):
        for i in range(n + 1):
            for j in range(n + 1):
                x = -size / 2 + size * i / n
                y = -size / 2 + size * j / n
                vertices.append((x, y, height(x, y) if layer == 0 else bottom))

    def vid(layer, i, j):
        return layer * (n + 1) * (n + 1) + i * (n + 1) + j

    triangles = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = vid(0, i, j), vid(0, i + 1, j), vid(0, i + 1, j + 1), vid(0, i, j + 1)
            triangles += [(a, b, c), (a, c, d)]  # top: counter-clockwise seen from +z
            a, b, c, d = vid(1, i, j), vid(1, i + 1, j), vid(1, i + 1, j + 1), vid(1, i, j + 1)
            triangles += [(a, c, b), (a, d, c)]  # bottom: facing -z
    rim = [(i, 0) for i in range(n)] + [(n, j) for j in range(n)] + [(i, n) for i in range(n, 0, -1)] + \
          [(0, j) for j in range(n, 0, -1)]  # counter-clockwise seen from +z
    for k in range(len(rim)):
        (i0, j0), (i1, j1) = rim[k], rim[(k + 1) % len(rim)]
        t0, t1, b0, b1 = vid(0, i0, j0), vid(0, i1, j1), vid(1, i0, j0), vid(1, i1, j1)
        triangles += [(b0, b1, t1), (b0, t1, t0)]  # outward
    return vertices, triangles


def stylus(radius=25.0, half_length=60.0, segments=16, rings=4):
    # A capsule along z: a pole, rings down the lower cap, up the upper cap, a pole.
    profile = [(0.0, -half_length - radius)]
    for k in range(1, rings + 1):
        a = -math.pi / 2 + (math.pi / 2) * k / rings
        profile.append((radius * math.cos(a), -half_length + radius * math.sin(a)))
    for k in range(0, rings):
        a = (math.pi / 2) * k / rings
        profile.append((radius * math.cos(a), half_length + radius * math.sin(a)))
    profile.append((0.0, half_length + radius))
    vertices = [(0.0, 0.0, profile[0][1])]
    for r, z in profile[1:-1]:
        for s in range(segments):
            a = 2 * math.pi * s / segments
            vertices.append((r * math.cos(a), r * math.sin(a), z))
    vertices.append((0.0, 0.0, profile[-1][1]))
    ring_count = len(profile) - 2
    top = len(vertices) - 1

    def vid(ring, s):
        return 1 + ring * segments + s % segments

    triangles = []
    for s in range(segments):
        triangles.append((0, vid(0, s + 1), vid(0, s)))
        triangles.append((top, vid(ring_count - 1, s), vid(ring_count - 1, s + 1)))
        for ring in range(ring_count - 1):
            a, b, c, d = vid(ring, s), vid(ring, s + 1), vid(ring + 1, s + 1), vid(ring + 1, s)
            triangles += [(a, b, c), (a, c, d)]
    return vertices, triangles


if __name__ == "__main__":
    with open(os.path.join(HERE, "haptic_hill.unurbs.json"), "w") as f:
        json.dump(hill(), f)
        f.write("\n")
    write_obj(os.path.join(HERE, "haptic_plate.obj"), "bumpy slab for haptic.json (make_haptic_models.py)",
              *bumpy_plate())
    write_obj(os.path.join(HERE, "haptic_tool.obj"), "stylus for haptic.json (make_haptic_models.py)", *stylus())
