#!/usr/bin/env python3
"""The accuracy study of talus (issue 5): error against run time.

For each problem (cantilever under self-weight, Kirsch hole, strip footing,
Salencon hole) and each formulation of the zones (tet4, tet4-nmd, hex-mixed,
tet10), runs talus on parameter files at four or more mesh sizes to a fixed
static tolerance (the unbalanced-force ratio), measures the error against the
closed form and the wall time of the run, writes results.csv, prints a
summary table and, when python3-matplotlib is installed, draws one log-log
plot of error against run time per problem (<problem>.png).

A formulation is only a parameter-file setting in subsection Deformable, so
formulations that this build of talus does not know (an unknown entry
'Element') are reported as "not built", and those a problem cannot use (for
example bricks for a tetrahedral mesh file) as "n/a" with talus's message.

Standard library only; plots need python3-matplotlib (Debian). Run from
anywhere:

    python3 contrib/verification/run_study.py [--talus build/talus]
        [--problems cantilever,kirsch,footing,salencon]
        [--elements tet4,tet4-nmd,hex-mixed,tet10] [--levels N] [--quick]
"""

import argparse
import base64
import csv
import glob
import math
import os
import re
import resource
import shutil
import struct
import subprocess
import sys
import time
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import hole_mesh  # noqa: E402

# ---- Formulations: the entries of subsection Deformable that select them ----

ELEMENTS = {
    "tet4": {},  # the default: constant-strain tetrahedra
    "tet4-nmd": {"Nodal mixed discretization": "true"},
    "hex-mixed": {"Element": "hex-mixed"},
    "tet10": {"Element": "tet10"},
}
LABELS = {
    "tet4": "4-node tetrahedra",
    "tet4-nmd": "4-node tetrahedra, nodal mixed",
    "hex-mixed": "hexahedra, mixed discretization",
    "tet10": "10-node tetrahedra",
}

# ---- Editing parameter files --------------------------------------------------


def set_entry(text, subsection, entry, value):
    """Sets `entry` of `subsection` (replacing its line, or adding one)."""
    lines = text.split("\n")
    inside = False
    start = None
    for k, line in enumerate(lines):
        stripped = line.split("#")[0].strip()
        if stripped == "subsection " + subsection:
            inside, start = True, k
            continue
        if inside and stripped == "end":
            lines.insert(k, "  set %s = %s" % (entry, value))
            return "\n".join(lines)
        if inside and re.match(r"set\s+" + re.escape(entry) + r"\s*=", stripped):
            lines[k] = "  set %s = %s" % (entry, value)
            return "\n".join(lines)
    if start is None:
        return text.rstrip("\n") + "\nsubsection %s\n  set %s = %s\nend\n" % (subsection, entry,
                                                                              value)
    raise ValueError("unterminated subsection " + subsection)


def vec(*values):
    return ", ".join("%.17g" % v for v in values)


# ---- Running talus and reading what it wrote -----------------------------------


class Run:
    """One talus run: its status, summary numbers and files."""

    def __init__(self):
        self.status = "ok"
        self.message = ""
        self.seconds = 0.0
        self.cpu_seconds = 0.0
        self.zones = 0
        self.gridpoints = 0
        self.steps = 0
        self.ratio = float("nan")
        self.stdout = ""
        self.out_dir = ""
        self.base = ""


def run_talus(talus, prm_text, work, name, timeout):
    out_dir = os.path.join(work, name)
    if os.path.isdir(out_dir):
        shutil.rmtree(out_dir)
    os.makedirs(out_dir)
    prm_text = set_entry(prm_text, "Output", "Directory", out_dir)
    prm_text = set_entry(prm_text, "Output", "Base name", "run")
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(prm_text)
    run = Run()
    run.out_dir, run.base = out_dir, "run"
    start = time.perf_counter()
    used = resource.getrusage(resource.RUSAGE_CHILDREN)
    try:
        p = subprocess.run([talus, prm], capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        run.status, run.message = "timeout", "over %g s" % timeout
        run.seconds = timeout
        return run
    run.seconds = time.perf_counter() - start
    now = resource.getrusage(resource.RUSAGE_CHILDREN)
    run.cpu_seconds = (now.ru_utime - used.ru_utime) + (now.ru_stime - used.ru_stime)
    run.stdout = p.stdout
    if p.returncode != 0:
        message = (p.stderr.strip().splitlines() or ["exit code %d" % p.returncode])[-1]
        message = message.replace(prm, name + ".prm")
        # 'Element' unknown (neither formulation merged) or refused with
        # "... is not built yet" (the other one merged).
        if "'Element'" in message and ("no such entry" in message or "not built" in message):
            run.status = "not built"
            why = re.search(r"'Deformable': ([^;]*)", message)
            message = "not in this talus: " + (why.group(1) if why else message)
        else:
            run.status = "n/a"
        run.message = message
        return run
    m = re.search(r"Zones:\s+(\d+) \w+[^,]*, (\d+) gridpoints", p.stdout)
    if m:
        run.zones, run.gridpoints = int(m.group(1)), int(m.group(2))
    m = re.search(r"Steps:\s+(\d+)", p.stdout)
    if m:
        run.steps = int(m.group(1))
    m = re.search(r"Unbalanced force ratio: (\S+)", p.stdout)
    if m:
        run.ratio = float(m.group(1))
    return run


def decode_array(attributes, text, header_width=4):
    """One DataArray's numbers: ASCII, or VTK's compressed binary form (a
    base64 header of 32-bit numbers (deal.II) or 64-bit ones (talus's own
    writers, header_type="UInt64"): the number of blocks, the block size, the
    last block's size and each block's compressed size; then the base64 of
    the blocks, each a zlib stream)."""
    if 'format="ascii"' in attributes:
        return [float(x) for x in text.split()]
    kind = re.search(r'type="(\w+)"', attributes).group(1)
    code, width = {"Float32": ("f", 4), "Float64": ("d", 8), "Int32": ("i", 4),
                   "UInt8": ("B", 1), "Int64": ("q", 8)}[kind]
    text = "".join(text.split())
    word = "<I" if header_width == 4 else "<Q"
    # The first three numbers, then the whole header once their count is known.
    first = base64.b64decode(text[:4 * ((3 * header_width + 2) // 3)])[:header_width]
    n_blocks = struct.unpack(word, first)[0]
    header_bytes = (3 + n_blocks) * header_width
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = struct.unpack("<%d%s" % (3 + n_blocks, word[1]),
                           base64.b64decode(text[:header_chars])[:header_bytes])
    data = base64.b64decode(text[header_chars:])
    raw, at = b"", 0
    for size in header[3:]:
        raw += zlib.decompress(data[at:at + size])
        at += size
    return list(struct.unpack("<%d%s" % (len(raw) // width, code), raw))


def read_vtu(path):
    """The data arrays of a VTU file by name, as lists of numbers; the points
    under "Points". Zone data that the writer puts at each of a cell's own
    points (deal.II's DataOut) come back one value per cell, and a stress
    written as a 3x3 tensor as six numbers (xx, yy, zz, xy, yz, zx)."""
    with open(path) as f:
        text = f.read()
    arrays = {}
    width = 8 if 'header_type="UInt64"' in text[:400] else 4
    points = re.search(r"<Points>\s*<DataArray([^>]*)>(.*?)</DataArray>", text, re.S)
    arrays["Points"] = decode_array(points.group(1), points.group(2), width)
    for m in re.finditer(r'<DataArray([^>]*)Name="([^"]+)"([^>]*)>(.*?)</DataArray>', text, re.S):
        if m.group(2) != "TIME":
            arrays[m.group(2)] = decode_array(m.group(1) + m.group(3), m.group(4), width)
    n_points = len(arrays["Points"]) // 3
    n_cells = len(arrays["offsets"])
    if "Points" in arrays and n_points != n_cells and n_points == 4 * n_cells:
        # DataOut: every cell has its own four points, so zone values repeat.
        for name in ("stress", "principal_stress", "plastic_state", "block_id"):
            if name in arrays:
                per_point = len(arrays[name]) // n_points
                arrays[name] = [v for c in range(n_cells)
                                for v in arrays[name][4 * c * per_point:(4 * c + 1) * per_point]]
    if "stress" in arrays and len(arrays["stress"]) == 9 * n_cells:
        t = arrays["stress"]
        arrays["stress"] = [t[9 * c + k] for c in range(n_cells) for k in (0, 4, 8, 1, 5, 2)]
    return arrays


def last_zone_frame(run):
    frames = sorted(glob.glob(os.path.join(run.out_dir, run.base + "_zones_*.vtu")))
    if not frames:
        raise RuntimeError("no zone output in " + run.out_dir)
    return read_vtu(frames[-1])


def cells(vtu):
    """Per cell: (centroid, corner point indices); the centroid is the mean of
    the cell's points (exact for tetrahedra, 10-node ones included, and for
    parallelepipeds)."""
    x = vtu["Points"]
    conn = [int(c) for c in vtu["connectivity"]]
    offsets = [int(o) for o in vtu["offsets"]]
    out = []
    first = 0
    for end in offsets:
        ids = conn[first:end]
        c = [sum(x[3 * i + d] for i in ids) / len(ids) for d in range(3)]
        out.append((c, ids))
        first = end
    return out


def least_squares(rows, rhs):
    """Least-squares solution by the normal equations, columns scaled."""
    n = len(rows[0])
    scale = [max(abs(r[j]) for r in rows) or 1.0 for j in range(n)]
    a = [[sum(r[i] * r[j] for r in rows) / (scale[i] * scale[j]) for j in range(n)]
         for i in range(n)]
    b = [sum(r[i] * y for r, y in zip(rows, rhs)) / scale[i] for i in range(n)]
    for k in range(n):  # Gauss elimination with partial pivoting
        p = max(range(k, n), key=lambda i: abs(a[i][k]))
        a[k], a[p], b[k], b[p] = a[p], a[k], b[p], b[k]
        for i in range(k + 1, n):
            f = a[i][k] / a[k][k]
            for j in range(k, n):
                a[i][j] -= f * a[k][j]
            b[i] -= f * b[k]
    x = [0.0] * n
    for k in reversed(range(n)):
        x[k] = (b[k] - sum(a[k][j] * x[j] for j in range(k + 1, n))) / a[k][k]
    return [x[j] / scale[j] for j in range(n)]


# ---- The problems ----------------------------------------------------------------
#
# Each problem gives its mesh levels, a parameter file for (level, element)
# and a measurement of the finished run: (computed, closed form, error).


class Cantilever:
    """10 m x 1 m x 1 m beam clamped at x = 0 under its own weight
    (parameters/verification/cantilever.prm): mean vertical displacement of
    the tip face against Timoshenko beam theory."""

    name = "cantilever"
    quantity = "tip deflection (m)"
    levels = [("edge 1/2", 0.5), ("edge 1/3", 1 / 3), ("edge 1/4", 0.25), ("edge 1/5", 0.2),
              ("edge 1/6", 1 / 6)]

    def __init__(self):
        L, A, I, rho, E, nu = 10.0, 1.0, 1.0 / 12.0, 2650.0, 1e10, 0.25
        G, q = E / (2 * (1 + nu)), rho * 9.81 * A
        self.exact = q * L ** 4 / (8 * E * I) + q * L * L / (2 * 5.0 / 6.0 * G * A)

    def parameter_file(self, level, work, element, ratio):
        with open(os.path.join(ROOT, "parameters", "verification", "cantilever.prm")) as f:
            text = f.read()
        text = set_entry(text, "Deformable", "Edge length", "%.17g" % level)
        text = set_entry(text, "Solver", "Damping", "global")
        text = set_entry(text, "Solver", "Target ratio", "%g" % ratio)
        text = set_entry(text, "Solver", "Steps", "1000000")
        return text

    def measure(self, run, level):
        vtu = last_zone_frame(run)
        x, u = vtu["Points"], vtu["displacement"]
        tip = [-u[3 * g + 2] for g in range(len(x) // 3)
               if abs(x[3 * g] - u[3 * g] - 10.0) < 1e-4]
        return sum(tip) / len(tip)

    def closed_form(self):
        return self.exact


class Kirsch:
    """Circular hole (a = 1 m) under unequal far-field stresses (vertical
    p = 0.1 MPa, horizontal K p, K = 0.5) in plane strain, a quarter model to
    the square of half-width L = 40 a (tests/deformable/kirsch_01.cc): the
    hoop stress at the wall at theta = 0 and 90 degrees, each from a
    least-squares fit to the zones of the first three rings and two sectors
    next to the axis, evaluated at the wall; the error is the larger of the
    two differences from Kirsch over the peak wall stress, 2.5 p (at 90
    degrees Kirsch's -0.5 p is a small difference of large terms)."""

    name = "kirsch"
    quantity = "wall hoop stress at 0 and 90 deg (Pa)"
    levels = [("%d sectors" % n, n) for n in (6, 8, 12, 16)]
    a, L, p, K, E, nu = 1.0, 40.0, 1e5, 0.5, 1e10, 0.25
    square = True

    def mesh(self, level, work, element):
        kind = "hex" if element == "hex-mixed" else "tet"
        path = os.path.join(work, "%s_%d_%s.msh" % (self.name, level, kind))
        nodes, elements, n_r, thickness = hole_mesh.build(self.a, self.L, level, self.square,
                                                          kind)
        hole_mesh.write_msh(path, nodes, elements)
        self.ring_ratio = (self.L / self.a) ** (1.0 / n_r)
        self.dtheta = 0.5 * math.pi / level
        return path, thickness

    def parameter_file(self, level, work, element, ratio):
        mesh, t = self.mesh(level, work, element)
        L, eps = self.L, 1e-6
        sx, sy = -self.K * self.p, -self.p
        text = """# Kirsch: circular hole under unequal far-field stresses (written by run_study.py)
subsection Model
  set Brick min = 0, 0, 0
  set Brick max = {L}, {L}, {t}
end
subsection Deformable
  set Groups          = rock
  set Mesh file       = {mesh}
  set Young's modulus = {E}
  set Poisson's ratio = {nu}
end
subsection Initial stress
  set Stress = {sx}, {sy}, {sz}, 0, 0, 0
end
subsection Boundary 1
  set Corner min      = -{eps}, -1, -1
  set Corner max      = {eps}, {big}, {big}
  set Held components = x
end
subsection Boundary 2
  set Corner min      = -1, -{eps}, -1
  set Corner max      = {big}, {eps}, {big}
  set Held components = y
end
subsection Boundary 3
  set Corner min      = -1, -1, -{eps}
  set Corner max      = {big}, {big}, {eps}
  set Held components = z
end
subsection Boundary 4
  set Corner min      = -1, -1, {tlo}
  set Corner max      = {big}, {big}, {thi}
  set Held components = z
end
subsection Boundary 5
  set Corner min = {Llo}, -1, -1
  set Corner max = {Lhi}, {big}, {big}
  set Condition  = pressure
  set Pressure   = {px}
end
subsection Boundary 6
  set Corner min = -1, {Llo}, -1
  set Corner max = {big}, {Lhi}, {big}
  set Condition  = pressure
  set Pressure   = {py}
end
subsection Solver
  set Mode         = static
  set Gravity      = 0, 0, 0
  set Damping      = global
  set Steps        = 1000000
  set Target ratio = {ratio}
  set History interval = 1000
end
subsection Output
  set Write VTU = true
end
""".format(L=L, t="%.17g" % t, mesh=mesh, E=self.E, nu=self.nu, sx=sx, sy=sy,
           sz=self.nu * (sx + sy), eps=eps, big=2 * L, tlo="%.17g" % (t - eps),
           thi="%.17g" % (t + eps), Llo=L - eps, Lhi=L + eps, px=-sx, py=-sy, ratio=ratio)
        return text

    def kirsch_hoop(self, r, theta):
        sx, sy = -self.K * self.p, -self.p
        m, d, rho = 0.5 * (sx + sy), 0.5 * (sx - sy), self.a ** 2 / r ** 2
        return m * (1 + rho) - d * (1 + 3 * rho * rho) * math.cos(2 * theta)

    def measure(self, run, level):
        vtu = last_zone_frame(run)
        s = vtu["stress"]
        zones = []
        for z, (c, _) in enumerate(cells(vtu)):
            r, theta = math.hypot(c[0], c[1]), math.atan2(c[1], c[0])
            cs, sn = math.cos(theta), math.sin(theta)
            stt = s[6 * z] * sn * sn + s[6 * z + 1] * cs * cs - 2 * s[6 * z + 3] * sn * cs
            zones.append((r, theta, stt))
        values = []
        for y_axis in (False, True):
            rows, rhs = [], []
            for r, theta, stt in zones:
                phi = 0.5 * math.pi - theta if y_axis else theta
                if r > self.a * self.ring_ratio ** 3 or phi > 2 * self.dtheta:
                    continue
                q, phi2 = self.a ** 2 / r ** 2 - 1, phi * phi
                rows.append([1.0, q, q * q, phi2, phi2 * q])
                rhs.append(stt)
            values.append(least_squares(rows, rhs)[0])
        return values

    def closed_form(self):
        """Kirsch's wall hoop stress at 0 and 90 degrees (Pa)."""
        return [-self.p * (3 - self.K), -self.p * (3 * self.K - 1)]


class Salencon(Kirsch):
    """Cylindrical hole (a = 1 m) in Mohr-Coulomb rock (phi = 20 deg, c =
    17 kPa, psi = 0) under p0 = 0.1 MPa, plane strain, quarter model to the
    circle R = 20 a (tests/deformable/salencon_01.cc): the plastic radius,
    where a least-squares fit f = alpha + beta / r^2 of the yield function of
    the zones within 4 a that never yielded reaches zero, against Salencon's
    R_p for this outer radius (2.0171 m; 2.0103 m in an infinite medium)."""

    name = "salencon"
    quantity = "plastic radius (m)"
    levels = [("%d sectors" % n, n) for n in (6, 8, 12, 16)]
    a, L, p0, E, nu, c, phi = 1.0, 20.0, 1e5, 2e10, 0.4, 17e3, 20.0
    square = False

    def __init__(self):
        sp = math.sin(math.radians(self.phi))
        self.Kp = (1 + sp) / (1 - sp)
        C = self.c / math.tan(math.radians(self.phi))
        self.Rp = self.a * (2 / (self.Kp + 1) * (self.p0 + C) / C) ** (1 / (self.Kp - 1))

    def parameter_file(self, level, work, element, ratio):
        mesh, t = self.mesh(level, work, element)
        eps, big = 1e-6, 2 * self.L
        return """# Salencon: cylindrical hole in Mohr-Coulomb rock (written by run_study.py)
subsection Model
  set Brick min = 0, 0, 0
  set Brick max = {L}, {L}, {t}
end
subsection Deformable
  set Groups           = rock
  set Mesh file        = {mesh}
  set Zone model       = mohr-coulomb
  set Young's modulus  = {E}
  set Poisson's ratio  = {nu}
  set Friction angle   = {phi}
  set Dilation angle   = 0
  set Cohesion         = {c}
  set Tensile strength = 1e30
end
subsection Initial stress
  set Stress = -{p0}, -{p0}, -{p0}, 0, 0, 0
end
subsection Boundary 1
  set Corner min      = -{eps}, -1, -1
  set Corner max      = {eps}, {big}, {big}
  set Held components = x
end
subsection Boundary 2
  set Corner min      = -1, -{eps}, -1
  set Corner max      = {big}, {eps}, {big}
  set Held components = y
end
subsection Boundary 3
  set Corner min      = -1, -1, -{eps}
  set Corner max      = {big}, {big}, {eps}
  set Held components = z
end
subsection Boundary 4
  set Corner min      = -1, -1, {tlo}
  set Corner max      = {big}, {big}, {thi}
  set Held components = z
end
subsection Boundary 5          # the outer circle, beyond 2a
  set Corner min = 2, {eps}, {eps}
  set Corner max = {big}, {big}, {tin}
  set Condition  = pressure
  set Pressure   = {p0}
end
subsection Boundary 6
  set Corner min = {eps}, 2, {eps}
  set Corner max = {big}, {big}, {tin}
  set Condition  = pressure
  set Pressure   = {p0}
end
subsection Solver
  set Mode         = static
  set Gravity      = 0, 0, 0
  set Damping      = local
  set Steps        = 1000000
  set Target ratio = {ratio}
  set History interval = 1000
end
subsection Output
  set Write VTU = true
end
""".format(L=self.L, t="%.17g" % t, mesh=mesh, E=self.E, nu=self.nu, phi=self.phi, c=self.c,
           p0=self.p0, eps=eps, big=big, tlo="%.17g" % (t - eps), thi="%.17g" % (t + eps),
           tin="%.17g" % (t - eps), ratio=ratio)

    def measure(self, run, level):
        vtu = last_zone_frame(run)
        principal = vtu["principal_stress"]
        state = vtu.get("plastic_state", [])
        rows, rhs = [], []
        for z, (c, _) in enumerate(cells(vtu)):
            r = math.hypot(c[0], c[1])
            s1, s3 = principal[3 * z], principal[3 * z + 2]  # ascending, tension positive
            f = (s1 - self.Kp * s3 + 2 * self.c * math.sqrt(self.Kp)) / self.p0
            # Zones that never yielded (the state's bit 4: yielded in shear
            # before): some yielded ones unload a little, off the surface.
            elastic = not (state and int(state[z]) & 4)
            if elastic and f > 1e-3 and r < 4 * self.a:
                rows.append([1.0, 1.0 / (r * r)])
                rhs.append(f)
        alpha, beta = least_squares(rows, rhs)
        return math.sqrt(-beta / alpha)

    def closed_form(self):
        """Salencon's plastic radius for the model's outer radius R loaded by
        p0 (the infinite medium's 2.0103 m is 0.3 % smaller): elastic
        sigma_r,t = A -/+ B / r^2 outside R_p (compression positive) with
        A - B / R^2 = p0, yield at R_p and sigma_r continuous there, solved by
        bisection (as tests/deformable/salencon_01.cc)."""
        Kp, c, p0, a, R = self.Kp, self.c, self.p0, self.a, self.L
        C = c / math.tan(math.radians(self.phi))

        def mismatch(rp):
            B = ((Kp - 1) * p0 + 2 * c * math.sqrt(Kp)) / ((Kp + 1) / rp ** 2 - (Kp - 1) / R ** 2)
            A = p0 + B / R ** 2
            return C * (rp / a) ** (Kp - 1) - C - (A - B / rp ** 2)

        lo, hi = a, 0.5 * R
        for _ in range(100):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if mismatch(mid) < 0 else (lo, mid)
        return 0.5 * (lo + hi)


class StripFooting:
    """Rigid smooth strip footing (B = 2 m) on a weightless Tresca layer (c =
    10 kPa, phi = psi = 0), plane strain, half model
    (parameters/verification/strip_footing.prm): the footing pressure after
    a prescribed settlement of 20 mm (1 % of B, five times the elastic
    settlement at collapse) and a static settling, against Prandtl's
    (2 + pi) c. The pressure is the vertical reaction of the footing's
    gridpoints over the area they stand for: out to midway between the last
    footing gridpoint (x = B/2) and the first free one."""

    name = "footing"
    quantity = "collapse pressure (Pa)"
    levels = [("edge 1/2", 0.5), ("edge 1/4", 0.25), ("edge 1/6", 1 / 6), ("edge 1/8", 0.125)]
    c = 1e4

    def parameter_file(self, level, work, element, ratio):
        with open(os.path.join(ROOT, "parameters", "verification", "strip_footing.prm")) as f:
            text = f.read()
        h = level
        # The footing moves 20 mm; the steps of the loading grow with the
        # zones across the model (a pulse crosses one zone per step or so).
        steps = int(round(4000 * 0.5 / h))
        text = set_entry(text, "Deformable", "Edge length", "%.17g" % h)
        text = set_entry(text, "Model", "Brick max", vec(5, h, 0))
        text = set_entry(text, "Boundary 2", "Velocity", vec(0, 0, -0.02 / steps))
        text = set_entry(text, "Boundary 2", "Velocity until", "%d" % steps)
        text = set_entry(text, "Boundary 6", "Corner min", vec(-1, h - 0.001, -4))
        text = set_entry(text, "Boundary 6", "Corner max", vec(6, h + 0.001, 1))
        text = set_entry(text, "Solver", "Target ratio", "%g" % ratio)
        text = set_entry(text, "Solver", "Steps", "1000000")
        text = set_entry(text, "Output", "Write VTU", "true")
        return text

    def measure(self, run, level):
        m = re.search(r"Reaction of Boundary 2 on the body: \S+, \S+, (\S+) N", run.stdout)
        # The footing's last gridpoint is at x = B/2 = 1 m; its nodal force
        # stands for the surface out to midway to the first free gridpoint.
        vtu = last_zone_frame(run)
        x, u = vtu["Points"], vtu["displacement"]
        # 1e-5 m: the VTU holds single precision.
        surface = [x[3 * g] - u[3 * g] for g in range(len(x) // 3)
                   if abs(x[3 * g + 2] - u[3 * g + 2]) < 1e-5]
        first_free = min(v for v in surface if v > 1.0 + 1e-5)
        half_width = 0.5 * (1.0 + first_free)
        return -float(m.group(1)) / (half_width * level)

    def closed_form(self):
        return (2 + math.pi) * self.c


PROBLEMS = {p.name: p for p in (Cantilever(), Kirsch(), StripFooting(), Salencon())}

# ---- The study --------------------------------------------------------------------

FIELDS = ["problem", "element", "mesh", "level", "zones", "gridpoints", "steps", "ratio", "seconds",
          "cpu_seconds",
          "computed", "exact", "error", "status", "note"]


def relative_error(value, exact):
    if isinstance(value, list):  # several values: the largest difference over the largest value
        return max(abs(v - e) for v, e in zip(value, exact)) / max(abs(e) for e in exact)
    return abs(value / exact - 1)


def fmt(v):
    if isinstance(v, list):
        return "; ".join("%.6g" % x for x in v)
    return "%.6g" % v if isinstance(v, float) else str(v)


def short(mesh):
    """'edge 1/4' -> '1/4', '8 sectors' -> '8s'."""
    return mesh.split()[-1] if mesh.startswith("edge") else mesh.split()[0] + "s"


def extrapolate(h, u):
    """Limit of u(h) = u0 + C h^p through three points (bisection on p)."""

    def mismatch(p):
        # u0 from the two finest, then how far the coarsest is off.
        c = (u[1] - u[2]) / (h[1] ** p - h[2] ** p)
        return u[0] - (u[2] - c * h[2] ** p) - c * h[0] ** p

    lo, hi = 0.2, 6.0
    if mismatch(lo) * mismatch(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        (lo, hi) = (mid, hi) if mismatch(lo) * mismatch(mid) > 0 else (lo, mid)
    p = 0.5 * (lo + hi)
    c = (u[1] - u[2]) / (h[1] ** p - h[2] ** p)
    return u[2] - c * h[2] ** p, p


def converged_cantilever(rows):
    """The reference 'converged' tip deflection: the finest 10-node answer
    if there is one, else the extrapolation of the best formulation's three
    finest meshes."""
    ok = [r for r in rows if r["problem"] == "cantilever" and r["status"] == "ok"]
    tet10 = [r for r in ok if r["element"] == "tet10"]
    if tet10:
        best = max(tet10, key=lambda r: r["zones"])
        return best["computed"], "finest tet10 (%s)" % best["mesh"]
    for element in ("hex-mixed", "tet4-nmd", "tet4"):
        runs = sorted([r for r in ok if r["element"] == element], key=lambda r: -r["level"])
        if len(runs) >= 3:
            runs = runs[-3:]
            e = extrapolate([r["level"] for r in runs], [r["computed"] for r in runs])
            if e:
                return e[0], "%s extrapolated from its three finest meshes (order %.2f)" % (
                    element, e[1])
    return None, ""


def plot(rows, problems, out_dir):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no plots: python3-matplotlib is not installed; "
              "bash contrib/install-dependencies.sh --study installs it)")
        return []
    markers = {"tet4": "o", "tet4-nmd": "s", "hex-mixed": "^", "tet10": "D"}
    written = []
    for problem in problems:
        panels = [(problem.name, "error against the closed form")]
        if problem.name == "cantilever":
            panels = [("cantilever", "against Timoshenko beam theory"),
                      ("cantilever-converged", "against the converged answer")]
        fig, axes = plt.subplots(1, len(panels), figsize=(6.4 * len(panels), 4.8), squeeze=False)
        for ax, (key, title) in zip(axes[0], panels):
            for element in ELEMENTS:
                runs = [r for r in rows if r["problem"] == key and r["element"] == element and
                        r["status"] == "ok" and r["error"] > 0]
                if not runs:
                    continue
                runs.sort(key=lambda r: r["cpu_seconds"])
                ax.loglog([r["cpu_seconds"] for r in runs], [r["error"] for r in runs],
                          marker=markers[element], label=LABELS[element])
                for r in runs:
                    ax.annotate(short(r["mesh"]), (r["cpu_seconds"], r["error"]),
                                textcoords="offset points", xytext=(4, 4), fontsize=7)
            ax.set_xlabel("run time (s): CPU time of the talus process, one core")
            ax.set_ylabel("relative error")
            ax.set_title("%s: %s\n%s" % (problem.name, problem.quantity, title), fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=8)
        fig.tight_layout()
        path = os.path.join(out_dir, problem.name + ".png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def main(argv):
    parser = argparse.ArgumentParser(description="talus accuracy study: error against run time")
    parser.add_argument("--talus", default=os.path.join(ROOT, "build", "talus"))
    parser.add_argument("--problems", default=",".join(PROBLEMS))
    parser.add_argument("--elements", default=",".join(ELEMENTS))
    parser.add_argument("--levels", type=int, default=0,
                        help="only the N coarsest meshes of each problem (0: all)")
    parser.add_argument("--quick", action="store_true", help="the two coarsest meshes only")
    parser.add_argument("--ratio", type=float, default=1e-5,
                        help="static tolerance: the unbalanced-force ratio every run reaches")
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "verification"),
                        help="folder for the runs' files")
    parser.add_argument("--output", default=HERE, help="folder for results.csv and the plots")
    parser.add_argument("--timeout", type=float, default=1200.0, help="seconds per run")
    parser.add_argument("--keep", action="store_true",
                        help="keep the rows of results.csv for the pairs of problem and element "
                        "not run now (add a formulation without rerunning the others)")
    parser.add_argument("--replot", action="store_true",
                        help="run nothing: table and plots from results.csv")
    args = parser.parse_args(argv)
    talus = os.path.abspath(args.talus)
    if not args.replot and not os.access(talus, os.X_OK):
        sys.exit("run_study: no talus executable at %s (build it, or give --talus)" % talus)
    problems = [PROBLEMS[p] for p in args.problems.split(",")]
    elements = args.elements.split(",")
    for e in elements:
        if e not in ELEMENTS:
            sys.exit("run_study: unknown element %s; allowed: %s" % (e, ", ".join(ELEMENTS)))
    os.makedirs(args.work, exist_ok=True)
    os.makedirs(args.output, exist_ok=True)
    n_levels = 2 if args.quick else args.levels
    csv_path = os.path.join(args.output, "results.csv")

    rows = []
    if args.keep or args.replot:
        rows = [r for r in read_csv(csv_path) if r["problem"] != "cantilever-converged"]
        if not args.replot:  # the pairs about to run start afresh
            rows = [r for r in rows if not (r["problem"] in args.problems.split(",") and
                                            r["element"] in elements)]
    study_start = time.perf_counter()
    if not args.replot:
        rows = run_all(args, talus, problems, elements, n_levels, rows, csv_path)
    problems = [p for p in PROBLEMS.values() if any(r["problem"] == p.name for r in rows)]
    elements = [e for e in ELEMENTS if any(r["element"] == e for r in rows)]
    for r in rows:  # the closed forms as this script has them
        if r["status"] == "ok":
            r["exact"] = PROBLEMS[r["problem"]].closed_form()
            r["error"] = relative_error(r["computed"], r["exact"])
            r["note"] = "" if r["note"] == "did not reach the ratio" and r["ratio"] < args.ratio * 1.005 else r["note"]

    # The cantilever against the converged answer as well.
    reference, how = converged_cantilever(rows)
    if reference:
        for r in [r for r in rows if r["problem"] == "cantilever" and r["status"] == "ok"]:
            extra = dict(r, problem="cantilever-converged", exact=reference,
                         note=("reference: " + how + ("; " + r["note"] if r["note"] else "")))
            extra["error"] = (abs(r["computed"] / reference - 1) if r["status"] == "ok"
                              else float("nan"))
            rows.append(extra)
        print("cantilever: converged tip deflection %.6g m (%s)" % (reference, how))
    write_csv(rows, csv_path)
    summary = summary_table(rows, problems, elements)
    print("\n" + summary)
    with open(os.path.join(args.output, "summary.md"), "w") as f:
        f.write(summary)
    print("Wrote %s and summary.md" % csv_path)
    for path in plot(rows, problems, args.output):
        print("Wrote %s" % path)
    print("Study time: %.0f s" % (time.perf_counter() - study_start))


def run_all(args, talus, problems, elements, n_levels, rows, csv_path):
    print("%-10s %-10s %-11s %7s %7s %8s %9s %8s  %-24s %-24s %9s  %s" %
          ("problem", "element", "mesh", "zones", "steps", "ratio", "wall (s)", "CPU (s)",
           "computed", "closed form", "error", "status"), flush=True)
    for problem in problems:
        levels = problem.levels[:n_levels] if n_levels else problem.levels
        for element in elements:
            skip = None
            for label, level in levels:
                name = "%s_%s_%s" % (problem.name, element, re.sub(r"\W+", "", label))
                row = {"problem": problem.name, "element": element, "mesh": label,
                       "level": level, "zones": 0, "gridpoints": 0, "steps": 0,
                       "ratio": float("nan"), "seconds": 0.0, "cpu_seconds": 0.0,
                       "computed": float("nan"), "exact": float("nan"), "error": float("nan"),
                       "status": "", "note": ""}
                if skip:
                    row["status"], row["note"] = skip
                else:
                    text = problem.parameter_file(level, args.work, element, args.ratio)
                    for entry, value in ELEMENTS[element].items():
                        text = set_entry(text, "Deformable", entry, value)
                    run = run_talus(talus, text, args.work, name, args.timeout)
                    row.update(zones=run.zones, gridpoints=run.gridpoints, steps=run.steps,
                               ratio=run.ratio, seconds=run.seconds, cpu_seconds=run.cpu_seconds,
                               status=run.status, note=run.message)
                    if run.status == "ok":
                        try:
                            value, exact = problem.measure(run, level), problem.closed_form()
                            row.update(computed=value, exact=exact,
                                       error=relative_error(value, exact))
                            if not run.ratio < args.ratio * 1.005:  # printed to 3 digits
                                row["note"] = "did not reach the ratio"
                        except Exception as e:  # a run whose output cannot be measured
                            row.update(status="failed", note="measuring: %s" % e)
                    elif run.status in ("not built", "n/a"):
                        skip = (run.status, run.message)  # the finer meshes would say the same
                rows.append(row)
                write_csv(rows, csv_path)  # as it goes: a long study stopped keeps its runs
                print("%-10s %-10s %-11s %7d %7d %8.1e %9.2f %8.2f  %-24s %-24s %9.2e  %s %s" %
                      (problem.name, element, label, row["zones"], row["steps"], row["ratio"],
                       row["seconds"], row["cpu_seconds"], fmt(row["computed"]),
                       fmt(row["exact"]), row["error"], row["status"], row["note"]), flush=True)
    return rows


def write_csv(rows, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(FIELDS)
        for r in rows:
            w.writerow([fmt(r[k]) if k in ("computed", "exact") else
                        ("%.6g" % r[k] if isinstance(r[k], float) else r[k]) for k in FIELDS])


def read_csv(path):
    if not os.path.exists(path):
        return []
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            for k in ("zones", "gridpoints", "steps"):
                r[k] = int(r[k])
            if "level" not in r:  # from the mesh label: 'edge 1/4', '8 sectors'
                n = r["mesh"].split()[-1] if r["mesh"].startswith("edge") else r["mesh"].split()[0]
                r["level"] = float(n) if "/" not in n else 1.0 / float(n.split("/")[1])
            for k in ("level", "ratio", "seconds", "cpu_seconds", "error"):
                r[k] = float(r[k])
            for k in ("computed", "exact"):
                values = [float(v) for v in r[k].split(";")]
                r[k] = values if len(values) > 1 else values[0]
            rows.append(r)
    return rows


def summary_table(rows, problems, elements):
    """A markdown table: per problem and element, the error and CPU time of
    each mesh, coarse to fine."""
    lines = ["| problem | element | relative error (CPU s of the run), coarse to fine |",
             "|---|---|---|"]
    for problem in problems:
        keys = [problem.name] + (["cantilever-converged"] if problem.name == "cantilever" else [])
        for key in keys:
            for element in elements:
                runs = [r for r in rows if r["problem"] == key and r["element"] == element]
                if not runs:
                    continue
                if runs[0]["status"] in ("not built", "n/a"):
                    lines.append("| %s | %s | %s: %s |" % (key, element, runs[0]["status"],
                                                          runs[0]["note"]))
                    continue
                cells_ = ["%s: %.2g (%.1f s)" % (short(r["mesh"]), r["error"], r["cpu_seconds"])
                          if r["status"] == "ok" else "%s: %s" % (short(r["mesh"]), r["status"])
                          for r in runs]
                lines.append("| %s | %s | %s |" % (key, element, ", ".join(cells_)))
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main(sys.argv[1:])
