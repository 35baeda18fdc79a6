#!/usr/bin/env python3
"""Writes SPD scenes that ../shared/data/spd does not hold, as NFF and as POV-Ray twins.

Eric Haines' Standard Procedural Databases (1987) are defined by their generators; the shared
data holds the output of four of them (balls, gears, mount, tetra). This script is our own
writer of seven more, from the geometry their public-domain sources describe (none of their
code): `jacks` (recursive jacks of cylinders and spheres), `lattice` (shiny spheres joined by
matte cylinders in a cube), `rings` (pyramids of objects made of six pentagonal rings of
cylinders and spheres, before a wall), `shells` (Pickover's shell of overlapping spheres),
`sombrero` (a height field of triangles), `teapot` (Newell's teapot tessellated into
triangles with vertex normals, on a checkerboard) and `tree` (Aono and Kunii's tree of cones
and spheres over a field). Each function's docstring gives its counts at a size factor `s`.
The generators write `sombrero`'s POV-Ray twin as a `height_field` of a TGA image; ours writes
the same triangles as the NFF file, so both renderers trace one geometry.

The NFF file follows NFF.TXT (`c` entities are open cones); the POV-Ray twin writes the same
camera (direction, right and up scaled by the frustum at the NFF field of view), the lights
with the intensity the generators give POV-Ray (usually `1/√n` for `n` lights: POV-Ray does
not share the light out; NFF readers do), `cone { … open }` for each cone, and textures from
the material's parameters: the generator's ambient, diffuse, Phong highlight, reflection (the
NFF `Ks`).

    python3 benches/spd/generate.py jacks|lattice|rings|shells|sombrero|teapot|tree [-s N] OUT_DIR
        # writes OUT_DIR/NAME[-sN].nff and .pov (the generator's default size: NAME)
"""

import argparse
import math
import os


def ring_points(tube_radius):
    """The 30 joints of the six rings: one pentagon in the xy plane, scaled so that the object
    with its tubes fits the unit ball, and five copies tipped over by the dihedral angle of
    the dodecahedron and turned about z by odd tenths of a turn."""
    scale = 1.0 / (1.0 + tube_radius)
    first = [(scale * math.cos(2 * math.pi * k / 5), scale * math.sin(2 * math.pi * k / 5), 0.0)
             for k in range(5)]
    tip = math.degrees(2.0 * math.acos(math.cos(math.pi / 3) / math.sin(math.pi / 5)))
    points = list(first)
    for ring in range(1, 6):
        turn = 180.0 * (2 * (ring - 1) + 1) / 5
        m = matrix_product(rotation(0, tip), rotation(2, turn))
        points += [apply(m, p) for p in first]
    return points


class Writer:
    """The same scene into an NFF and a POV-Ray file."""

    def __init__(self, nff, pov):
        self.nff, self.pov = nff, pov
        self.declared, self.current = {}, None
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

    def light(self, p, intensity):
        """NFF lights carry no intensity (readers share one out); POV-Ray's get the
        generator's, usually `1/√n` for `n` lights."""
        self.nff.write("l %g %g %g\n" % p)
        k = intensity
        self.pov.write("light_source {\n    <%g, %g, %g> color red %g green %g blue %g\n"
                       "} // light\n\n" % (*p, k, k, k))

    def material(self, rgb, kd, ks, phong, shine, ka=0.0):
        """NFF `f r g b Kd Ks shine T ior` (opaque); a POV-Ray texture with the same terms and
        the generator's ambient `ka` (NFF has none). Written when it changes; a texture already
        declared is named again."""
        key = (rgb, kd, ks, phong, shine, ka)
        if key == self.current:
            return
        self.current = key
        self.nff.write("f %g %g %g %g %g %g 0 0\n" % (*rgb, kd, ks, shine))
        if key in self.declared:
            self.texture = self.declared[key]
            return
        finish = "        ambient %g\n        diffuse %g\n" % (ka, kd)
        if phong:
            finish += "        phong %g  phong_size %g\n" % (phong, shine)
        if ks:
            finish += "        reflection %g\n" % ks
        self.texture = "txt%03d" % (len(self.declared) + 1)
        self.declared[key] = self.texture
        self.pov.write("#declare %s = texture {\n    pigment {\n        color red %g green %g "
                       "blue %g\n    } // pigment\n    finish {\n%s    } // finish\n} // texture "
                       "%s\n\n" % (self.texture, *rgb, finish, self.texture))

    def polygon(self, vertices):
        self.nff.write("p %d\n" % len(vertices) + "".join("%g %g %g\n" % v for v in vertices))
        body = ",\n".join("        <%g, %g, %g>" % v for v in vertices)
        self.pov.write("polygon {\n    %d,\n%s\n    texture { %s }\n}\n\n"
                       % (len(vertices), body, self.texture))

    def triangle(self, vertices):
        """NFF's `p 3`, POV-Ray's `triangle` (as the SPD's own POV-Ray writer has it)."""
        self.nff.write("p 3\n" + "".join("%g %g %g\n" % v for v in vertices))
        body = ",\n".join("    <%g, %g, %g>" % v for v in vertices)
        self.pov.write("triangle {\n%s\n    texture { %s }\n}\n\n" % (body, self.texture))

    def smooth_triangle(self, vertices, normals):
        """NFF's `pp` (a polygon with a normal at each vertex), POV-Ray's `smooth_triangle`."""
        self.nff.write("pp 3\n" + "".join("%g %g %g %g %g %g\n" % (*v, *n)
                                          for v, n in zip(vertices, normals)))
        body = ",\n".join("    <%g, %g, %g>, <%g, %g, %g>" % (*v, *n)
                           for v, n in zip(vertices, normals))
        self.pov.write("smooth_triangle {\n%s\n    texture { %s }\n}\n\n" % (body, self.texture))

    def cone(self, base, base_r, apex, apex_r):
        """An open cone (a cylinder when the radii are equal), NFF's `c`."""
        self.nff.write("c\n%g %g %g %g\n%g %g %g %g\n" % (*base, base_r, *apex, apex_r))
        self.pov.write("cone {\n    <%g, %g, %g>, %g,\n    <%g, %g, %g>, %g open\n"
                       "    texture { %s }\n}\n\n" % (*apex, apex_r, *base, base_r, self.texture))

    def sphere(self, c, r):
        self.nff.write("s %g %g %g %g\n" % (*c, r))
        self.pov.write("sphere { <%g, %g, %g>, %g  texture { %s } }\n\n" % (*c, r, self.texture))


def rings(w, size):
    """Pyramids of objects of six pentagonal rings joining the midpoints of a dodecahedron's
    edges (each ring five cylinders and five spheres at the joints), layer `k` holding `k²`
    objects, before a white wall, seen along the pyramid's axis; three lights.
    `s² + (s − 1)² + … + 1` objects of 30 cylinders and 30 spheres (`s = 7`, the default:
    4 200 of each)."""
    radius = 0.07412  # the tubes' and joints' radius
    spread = 1.0 / math.sin(math.pi / 8)  # layers apart along y; the pyramid's x, z pitch is 1
    w.background((0.078, 0.361, 0.753))
    eye = (-1.0, -spread, 0.5)
    w.view(eye, (eye[0], eye[1] + 1.0, eye[2]), (0.0, 0.0, 1.0), 45.0, 1.0, 512)
    for p in [(3.0, -spread, 3.0), (-4.0, -spread, 1.0), (2.0, -spread, -4.0)]:
        w.light(p, 1.0 / math.sqrt(3))
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
                    w.cone(base, radius, apex, radius)
                    w.sphere(base, radius)


def matrix_product(a, b):
    """4 × 4 matrices acting on row vectors `[x y z 1]` on the left: `p·(a·b)` applies `a`,
    then `b`."""
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def rotation(axis, degrees):
    """Counter-clockwise about the x (0), y (1) or z (2) axis, for row vectors."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    m = [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m[i][i], m[i][j], m[j][i], m[j][j] = c, s, -s, c
    return m


def apply(m, p):
    return tuple(p[0] * m[0][j] + p[1] * m[1][j] + p[2] * m[2][j] + m[3][j] for j in range(3))


def tree(w, size):
    """Aono and Kunii's tree (IEEE CG&A, May 1984): each branch an open cone with a sphere at
    its tip, two sub-branches grown from the tip by fixed rotations, contractions and a unit
    lift, over a green field; seven lights. `2^(s+1) − 1` cones and as many spheres (`s = 11`,
    the default: 4 095)."""
    w.background((0.078, 0.361, 0.753))
    w.view((4.5, 0.4, 2.0), (0.0, 0.0, 1.5), (0.0, 0.0, 1.0), 45.0, 1.0, 512)
    lights = [(-5.0, 5.0, 50.0), (30.0, -30.0, 30.0), (-40.0, -30.0, 20.0), (10.0, 30.0, 40.0),
              (-30.0, 40.0, 10.0), (50.0, 25.0, 20.0), (-10.0, -60.0, 30.0)]
    for p in lights:
        w.light(p, 1.0 / math.sqrt(len(lights)))
    w.material((0.2, 0.7, 0.2), 1.0, 0.0, 0.0, 0.0)
    w.polygon([(50.0, 50.0, 0.0), (-50.0, 50.0, 0.0), (-50.0, -50.0, 0.0), (50.0, -50.0, 0.0)])
    w.material((0.55, 0.4, 0.2), 1.0, 0.0, 0.0, 0.0)
    # (branching angle about x, divergence about z, contraction) of the two sub-branches.
    steps = []
    for angle, divergence, contraction in [(40.0, 90.0, 0.65), (25.0, 140.0 + 90.0, 0.70)]:
        lift = [[contraction if i == j else 0.0 for j in range(4)] for i in range(4)]
        lift[3][3], lift[3][2] = 1.0, 1.0
        steps.append(matrix_product(matrix_product(rotation(0, angle), rotation(2, divergence)),
                                    lift))
    width, taper = 0.15, 0.67  # base radius per unit of scale; tip radius / base radius

    def grow(m, scale, depth):
        base, apex = apply(m, (0.0, 0.0, 0.0)), apply(m, (0.0, 0.0, 1.0))
        r = scale * width
        w.cone(base, r, apex, r * taper)
        w.sphere(apex, r * taper)
        if depth > 0:
            for step in steps:
                grow(matrix_product(step, m), scale * taper, depth - 1)

    grow([[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)], 1.0, size)


def shells(w, size):
    """Pickover's sea shell (IEEE CG&A, November 1989): spheres along a logarithmic spiral,
    radius `r = e^(0.15·θ)` at `(r·sin θ, r·cos θ, −2r)`, overlapping heavily, many tiny; one
    light. `180·2^s + 1` spheres (`s = 5`, the default: 5 761)."""
    w.background((0.078, 0.361, 0.753))
    w.view((-6.0, -60.0, 35.0), (0.0, 8.0, -15.0), (0.0, 0.0, 1.0), 45.0, 0.5, 512)
    w.light((-100.0, -100.0, 100.0), 1.0)
    w.material((1.0, 0.8, 0.4), 0.8, 0.2, 0.5, 10.0)
    steps = 180 * 2 ** size
    for i in range(-(steps * 2 // 3), steps // 3 + 1):
        angle = 3.0 * 6.0 * math.pi * i / steps
        r = math.exp(0.15 * angle)
        w.sphere((r * math.sin(angle), r * math.cos(angle), -2.0 * r), r)


def lattice(w, size):
    """A cubic lattice of shiny spheres joined by matte cylinders (red along x, green along y,
    blue along z) in the unit cube, seen from a corner; six lights. `(s + 1)³` spheres and
    `3·s·(s + 1)²` cylinders (`s = 12`, the default: 2 197 and 6 084)."""
    big, small = 0.25 / size, 1.0 / 16.0 / size  # sphere and cylinder radii
    gap = big * (1.0 - math.sqrt(0.25)) * 0.99  # cylinders start inside the spheres
    w.background((0.078, 0.361, 0.753))
    mid = ((size >> 1) + 0.5) / size
    w.view((mid, 1.0, 1.0 - 1.0 / (size << 1)), (mid, -1.0, -1.0 - 1.0 / (size << 1)),
           (0.2, 1.0, 0.0), 60.0, 0.0, 512)
    for p in [(2.0, 0.5, 0.5), (-1.0, 0.5, 0.5), (0.5, 2.0, 0.5), (0.5, -1.0, 0.5),
              (0.5, 0.5, 2.0), (0.5, 0.5, -1.0)]:
        w.light(p, 1.0 / math.sqrt(6))
    colours = [(0.9, 0.1, 0.1), (0.1, 0.9, 0.1), (0.1, 0.1, 0.9)]
    for x in range(size + 1):
        for y in range(size + 1):
            for z in range(size + 1):
                c = (x / size, y / size, z / size)
                w.material((0.9, 0.9, 0.9), 0.5, 0.5, 0.5, 37.0)
                w.sphere(c, big)
                for axis, n in enumerate((x, y, z)):
                    if n == size:
                        continue
                    w.material(colours[axis], 0.99, 0.0, 0.0, 0.0, ka=0.1)
                    base, apex = list(c), list(c)
                    base[axis] += gap
                    apex[axis] += 1.0 / size - gap
                    w.cone(tuple(base), small, tuple(apex), small)


def bezier_patches(path):
    """The bicubic patches of a `.bpt` file (count, then per patch `3 3` and 16 points, row by
    row): lists of 4 rows of 4 points."""
    words = open(path).read().split()
    count, at, patches = int(words[0]), 1, []
    for _ in range(count):
        assert words[at:at + 2] == ["3", "3"], "bicubic patches only"
        at += 2
        points = [tuple(float(x) for x in words[at + 3 * k:at + 3 * k + 3]) for k in range(16)]
        at += 48
        patches.append([points[4 * r:4 * r + 4] for r in range(4)])
    return patches


def bernstein3(x):
    """The cubic Bernstein polynomials at `x` and their derivatives."""
    y = 1.0 - x
    return ([y * y * y, 3 * x * y * y, 3 * x * x * y, x * x * x],
            [-3 * y * y, 3 * y * y - 6 * x * y, 6 * x * y - 3 * x * x, 3 * x * x])


def teapot(w, size):
    """Newell's teapot (with Crow's bottom, `scenes/teapot.bpt`), each of its 32 patches cut
    into `s × s` cells of two triangles with the patch normals at their corners (`pp`), on a
    checkerboard of `s × s` squares; two lights. `64·s² − 8·s` triangles once those degenerate
    at the lid's and the bottom's centre are dropped (`s = 6`, the default: 2 256), `s²`
    squares."""
    w.background((0.078, 0.361, 0.753))
    w.view((4.86, 7.2, 5.4), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 45.0, 1.0, 512)
    for p in [(-3.1, 9.8, 12.1), (11.3, 5.1, 8.8)]:
        w.light(p, 1.0 / math.sqrt(2))
    # The checkerboard: the squares with an odd index sum white, then the others grey.
    for colour, parity in [((1.0, 1.0, 1.0), 1), ((0.5, 0.5, 0.5), 0)]:
        w.material(colour, 0.5, 0.5, 0.5, 30.0)
        for i in range(size):
            for j in range(size):
                if (i + j) % 2 != parity:
                    continue
                x0, x1 = (4.0 * (2.0 * (i + k) / size - 1.0) for k in (0, 1))
                y0, y1 = (4.0 * (2.0 * (j + k) / size - 1.0) for k in (0, 1))
                w.polygon([(x0, y0, 0.0), (x1, y0, 0.0), (x1, y1, 0.0), (x0, y1, 0.0)])
    w.material((1.0, 0.5, 0.1), 0.75, 0.25, 0.25, 37.0)
    here = os.path.dirname(os.path.abspath(__file__))
    for g in bezier_patches(os.path.join(here, "..", "..", "scenes", "teapot.bpt")):

        def point(s, t):
            (bs, ds), (bt, dt) = bernstein3(s), bernstein3(t)
            p = [sum(bs[r] * bt[c] * g[r][c][k] for r in range(4) for c in range(4))
                 for k in range(3)]
            ps = [sum(ds[r] * bt[c] * g[r][c][k] for r in range(4) for c in range(4))
                  for k in range(3)]
            pt = [sum(bs[r] * dt[c] * g[r][c][k] for r in range(4) for c in range(4))
                  for k in range(3)]
            n = (pt[1] * ps[2] - pt[2] * ps[1], pt[2] * ps[0] - pt[0] * ps[2],
                 pt[0] * ps[1] - pt[1] * ps[0])
            length = math.sqrt(sum(c * c for c in n))
            return tuple(p), tuple(c / length for c in n) if length > 0 else (0.0, 0.0, 0.0)

        for i in range(size):
            for j in range(size):
                # Corners 0..3 of the cell: (i, j), (i, j+1), (i+1, j+1), (i+1, j).
                corners = [point((i + (k // 2)) / size, (j + (1 if k % 3 else 0)) / size)
                           for k in range(4)]
                for tri in ([0, 1, 2], [2, 3, 0]):
                    v = [corners[k][0] for k in tri]
                    n = [corners[k][1] for k in tri]
                    # A corner on the axis is a cusp (the lid's knob, the bottom's centre):
                    # two there make the triangle degenerate; one takes the axis's normal.
                    on_axis = [k for k in range(3) if abs(v[k][0]) < 1e-4 and abs(v[k][1]) < 1e-4]
                    if len(on_axis) > 1:
                        continue
                    for k in on_axis:
                        n[k] = (0.0, 0.0, 1.0 if v[k][2] > 1.5 else -1.0)
                    w.smooth_triangle(v, n)


def phong_power(degrees):
    """The highlight exponent whose lobe falls to half at `degrees` off the mirror direction,
    as the generators turn their highlight angle into NFF's `Shine` and POV-Ray's
    `phong_size`."""
    return math.log(0.5) / math.log(math.cos(math.radians(degrees)))


def jacks(w, size):
    """Enzmann's recursive jacks: a jack (three crossed cylinders, a sphere at each of their six
    ends) with a half-size copy of the whole in each of its eight octants, tilted by −20° about
    y, then −30° about x; one light. `9·(8^s − 1)/7` objects (`s = 1`, the default: one jack
    of 9; `s = 4`: 5 265)."""
    w.background((0.2, 0.05, 0.2))
    w.view((0.0, 0.0, -8.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 25.0, 0.001, 256)
    w.light((-10.0, 3.0, -20.0), 1.0)
    w.material((0.737, 0.561, 0.561), 0.7, 0.7, 0.4, phong_power(20.0), ka=0.1)
    tilt = matrix_product(rotation(1, -20.0), rotation(0, -30.0))

    def place(offset, scale, p):
        return apply(tilt, tuple(o + scale * c for o, c in zip(offset, p)))

    def jack(offset, scale, depth):
        arm = 0.75 * scale  # the jack is drawn at three quarters of its cell
        for axis in range(3):
            end = [0.0, 0.0, 0.0]
            end[axis] = 1.0
            w.cone(place(offset, arm, tuple(-c for c in end)), 0.1 * arm,
                   place(offset, arm, tuple(end)), 0.1 * arm)
        for axis in range(3):
            for sign in (1.0, -1.0):
                end = [0.0, 0.0, 0.0]
                end[axis] = sign
                w.sphere(place(offset, arm, tuple(end)), 0.2 * arm)
        if depth < size:
            for i in (-0.5, 0.5):
                for j in (-0.5, 0.5):
                    for k in (-0.5, 0.5):
                        child = tuple(o + scale * c for o, c in zip(offset, (i, j, k)))
                        jack(child, 0.5 * scale, depth + 1)

    jack((0.0, 0.0, 0.0), 1.0, 1)


def sombrero(w, size):
    """Enzmann's sombrero: the height field `y = −3 + cos(2πr)·e^(−r)` (`r` the distance from
    the axis) sampled on an `n × n` grid of `[−4, 4)²` and drawn over `[−4, 4]²` as two flat
    triangles a cell, shiny red; one light. `n = 32·2^(s−1)`, `2·(n − 1)²` triangles
    (`s = 1`, the default: 1 922; `s = 4`: 130 050)."""
    w.background((0.078, 0.361, 0.753))
    w.view((0.0, 5.0, -8.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 40.0, 0.01, 512)
    w.light((10.0, 10.0, -10.0), 1.0)
    w.material((1.0, 0.1, 0.1), 0.8, 0.0, 0.5, phong_power(40.0), ka=0.1)
    n = 32 << (size - 1)
    # Sampled at −4 + 8k/n, drawn at −4 + 8k/(n − 1): the generator's two spacings.
    heights = [[math.cos(2.0 * math.pi * math.hypot(-4.0 + 8.0 * j / n, -4.0 + 8.0 * i / n))
                * math.exp(-math.hypot(-4.0 + 8.0 * j / n, -4.0 + 8.0 * i / n))
                for j in range(n)] for i in range(n)]
    step = 8.0 / (n - 1)

    def vertex(i, j):
        return (-4.0 + j * step, -3.0 + heights[i][j], -4.0 + i * step)

    for i in range(n - 1):
        for j in range(n - 1):
            w.triangle([vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)])
            w.triangle([vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)])


GENERATORS = {"jacks": (jacks, 1), "lattice": (lattice, 12), "rings": (rings, 7),
              "shells": (shells, 5), "sombrero": (sombrero, 1), "teapot": (teapot, 6),
              "tree": (tree, 11)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", choices=sorted(GENERATORS))
    ap.add_argument("-s", "--size", type=int, help="size factor (default: the generator's)")
    ap.add_argument("out_dir")
    args = ap.parse_args()
    generate, default = GENERATORS[args.scene]
    size = default if args.size is None else args.size
    if size < 1:
        ap.error("the size factor is at least 1")
    name = args.scene if size == default else "%s-s%d" % (args.scene, size)
    os.makedirs(args.out_dir, exist_ok=True)
    base = os.path.join(args.out_dir, name)
    with open(base + ".nff", "w") as nff, open(base + ".pov", "w") as pov:
        generate(Writer(nff, pov), size)
    print(base + ".nff", base + ".pov")


if __name__ == "__main__":
    main()
