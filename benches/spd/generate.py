#!/usr/bin/env python3
"""Writes SPD scenes that ../shared/data/spd does not hold, as NFF and as POV-Ray twins.

Eric Haines' Standard Procedural Databases (1987) are defined by their generators; the shared
data holds the output of four of them (balls, gears, mount, tetra). This script is our own
writer of another one, from the generator's geometry as its source describes it (public
domain): `rings`, pyramids of objects made of six pentagonal rings that join the midpoints of
a dodecahedron's edges, each ring 5 cylinders and 5 spheres, in front of a white wall, seen from
the pyramid's apex direction, three lights. Size factor `s` gives s² + (s−1)² + … + 1 objects,
30 cylinders and 30 spheres each (`s = 7`, the default: 4 200 of each).

The NFF file follows NFF.TXT (`c` entities are open cones, here cylinders); the POV-Ray twin
writes the same camera (direction, right and up scaled by the frustum at the NFF field of
view), lights scaled by 1/√3 (POV-Ray does not normalise three lights; NFF readers do),
`cone { … open }` for each cylinder, and textures from the material's parameters: diffuse,
Phong highlight, reflection (the NFF `Ks`).

    python3 benches/spd/generate.py rings [-s N] OUT_DIR   # writes OUT_DIR/rings[-sN].{nff,pov}
"""

import argparse
import math
import os


def rotate_x(v, a):
    x, y, z = v
    c, s = math.cos(a), math.sin(a)
    return (x, y * c - z * s, y * s + z * c)


def rotate_z(v, a):
    x, y, z = v
    c, s = math.cos(a), math.sin(a)
    return (x * c - y * s, x * s + y * c, z)


def ring_points(tube_radius):
    """The 30 joints of the six rings: one pentagon in the xy plane, scaled so that the object
    with its tubes fits the unit ball, and five copies tipped over by the dihedral angle of
    the dodecahedron and turned about z by odd tenths of a turn."""
    scale = 1.0 / (1.0 + tube_radius)
    first = [(scale * math.cos(2 * math.pi * k / 5), scale * math.sin(2 * math.pi * k / 5), 0.0)
             for k in range(5)]
    tip = 2.0 * math.acos(math.cos(math.pi / 3) / math.sin(math.pi / 5))
    points = list(first)
    for ring in range(1, 6):
        turn = math.pi * (2 * (ring - 1) + 1) / 5
        points += [rotate_z(rotate_x(p, tip), turn) for p in first]
    return points


class Writer:
    """The same scene into an NFF and a POV-Ray file."""

    def __init__(self, nff, pov):
        self.nff, self.pov = nff, pov
        self.textures = 0
        self.pov.write("// POV-Ray 3 scene file, written by benches/spd/generate.py\n")

    def background(self, rgb):
        self.nff.write("b %g %g %g\n" % rgb)
        self.pov.write("background { color red %g green %g blue %g }\n\n" % rgb)

    def view(self, eye, at, up, fov, hither, res):
        self.nff.write("v\nfrom %g %g %g\nat %g %g %g\nup %g %g %g\nangle %g\nhither %g\n"
                       "resolution %d %d\n" % (*eye, *at, *up, fov, hither, res, res))
        norm = lambda v: tuple(c / math.sqrt(sum(x * x for x in v)) for c in v)
        cross = lambda a, b: (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                              a[0] * b[1] - a[1] * b[0])
        view = norm(tuple(a - e for a, e in zip(at, eye)))
        right = norm(cross(norm(up), view))
        upv = norm(cross(view, right))
        height = 2.0 * math.tan(math.pi * fov / 360.0)
        self.pov.write("camera {\n    location <%g, %g, %g>\n    direction <%g, %g, %g>\n"
                       "    right     <%g, %g, %g>\n    up        <%g, %g, %g>\n} // camera\n\n"
                       % (*eye, *view, *(-height * c for c in right), *(height * c for c in upv)))

    def light(self, p, lights):
        self.nff.write("l %g %g %g\n" % p)
        k = 1.0 / math.sqrt(lights)
        self.pov.write("light_source {\n    <%g, %g, %g> color red %g green %g blue %g\n"
                       "} // light\n\n" % (*p, k, k, k))

    def material(self, rgb, kd, ks, phong, shine):
        """NFF `f r g b Kd Ks shine T ior` (opaque); POV-Ray texture with the same terms."""
        self.nff.write("f %g %g %g %g %g %g 0 0\n" % (*rgb, kd, ks, shine))
        self.textures += 1
        finish = "        ambient 0\n        diffuse %g\n" % kd
        if phong:
            finish += "        phong %g  phong_size %g\n" % (phong, shine)
        if ks:
            finish += "        reflection %g\n" % ks
        self.texture = "txt%03d" % self.textures
        self.pov.write("#declare %s = texture {\n    pigment {\n        color red %g green %g "
                       "blue %g\n    } // pigment\n    finish {\n%s    } // finish\n} // texture "
                       "%s\n\n" % (self.texture, *rgb, finish, self.texture))

    def polygon(self, vertices):
        self.nff.write("p %d\n" % len(vertices) + "".join("%g %g %g\n" % v for v in vertices))
        body = ",\n".join("        <%g, %g, %g>" % v for v in vertices)
        self.pov.write("polygon {\n    %d,\n%s\n    texture { %s }\n}\n\n"
                       % (len(vertices), body, self.texture))

    def cylinder(self, base, apex, r):
        self.nff.write("c\n%g %g %g %g\n%g %g %g %g\n" % (*base, r, *apex, r))
        self.pov.write("cone {\n    <%g, %g, %g>, %g,\n    <%g, %g, %g>, %g open\n"
                       "    texture { %s }\n}\n\n" % (*apex, r, *base, r, self.texture))

    def sphere(self, c, r):
        self.nff.write("s %g %g %g %g\n" % (*c, r))
        self.pov.write("sphere { <%g, %g, %g>, %g  texture { %s } }\n\n" % (*c, r, self.texture))


def rings(w, size):
    radius = 0.07412  # the tubes' and joints' radius
    spread = 1.0 / math.sin(math.pi / 8)  # layers apart along y; the pyramid's x, z pitch is 1
    w.background((0.078, 0.361, 0.753))
    eye = (-1.0, -spread, 0.5)
    w.view(eye, (eye[0], eye[1] + 1.0, eye[2]), (0.0, 0.0, 1.0), 45.0, 1.0, 512)
    for p in [(3.0, -spread, 3.0), (-4.0, -spread, 1.0), (2.0, -spread, -4.0)]:
        w.light(p, 3)
    # The wall: white, just filling the 45° view (plus 1 %) behind the last layer.
    w.material((1.0, 1.0, 1.0), 1.0, 0.0, 0.0, 0.0)
    wy = spread * (size + 1)
    wxz = 1.01 * (wy - eye[1]) * math.tan(math.pi / 8)
    w.polygon([(wxz + eye[0], wy, wxz + eye[2]), (-wxz + eye[0], wy, wxz + eye[2]),
               (-wxz + eye[0], wy, -wxz + eye[2]), (wxz + eye[0], wy, -wxz + eye[2])])
    colours = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 1, 1), (1, 0, 1), (1, 1, 0)]
    joints = ring_points(radius)
    for depth in range(size):
        y = spread * (depth + 1)
        for iz in range(depth + 1):
            z = 2 * iz - depth
            for ix in range(depth + 1):
                x = 2 * ix - depth
                for k in range(30):
                    if k % 5 == 0:
                        w.material(tuple(float(c) for c in colours[k // 5]), 0.5, 0.2, 0.3, 37.0)
                    prev = k + 4 if k % 5 == 0 else k - 1
                    base = tuple(a + b for a, b in zip(joints[k], (x, y, z)))
                    apex = tuple(a + b for a, b in zip(joints[prev], (x, y, z)))
                    w.cylinder(base, apex, radius)
                    w.sphere(base, radius)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", choices=["rings"])
    ap.add_argument("-s", "--size", type=int, default=7, help="size factor (default 7)")
    ap.add_argument("out_dir")
    args = ap.parse_args()
    if args.size < 1:
        ap.error("the size factor is at least 1")
    name = args.scene if args.size == 7 else "%s-s%d" % (args.scene, args.size)
    os.makedirs(args.out_dir, exist_ok=True)
    base = os.path.join(args.out_dir, name)
    with open(base + ".nff", "w") as nff, open(base + ".pov", "w") as pov:
        rings(Writer(nff, pov), args.size)
    print(base + ".nff", base + ".pov")


if __name__ == "__main__":
    main()
