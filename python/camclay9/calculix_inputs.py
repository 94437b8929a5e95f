"""The inputs of input/abaqus/ (issues #6 and 21): `write(outdir)` writes them; the script
tools/calculix/make_inputs.py runs it. The files are committed; tests/calculix checks that they equal what it
writes. Two dialects of the same keyword syntax, one deck per test and host:
- CalculiX 2.20 (triaxial_*.inp, conventions_c3d8.inp): the decks run and compared by tests/calculix.
- Abaqus/Standard (*_abaqus.inp): the one-element triaxial creep test and the cylinder in the keyword
  syntax of the Abaqus Keywords Reference, each keyword checked against its page
  (input/abaqus/KEYWORDS.md). They differ from the CalculiX decks only where the two codes differ: the
  initial stress by element set (CalculiX: one line per element and integration point), no GLOBAL
  parameter on *EL PRINT (CalculiX's own), output to the output database instead of .frd, a data line on
  *SOLID SECTION, and Abaqus' default convergence controls (the tight *CONTROLS make CalculiX's
  linearly converging Newton, on a symmetrised tangent, reach 1e-8; Abaqus solves with the unsymmetric
  tangent of UNSYMM).
Cards follow docs/umat.md: material ABAQUS_WOODFORD, CONSTANTS=20 (CalculiX keeps at most 21), bedding
normal through *ORIENTATION (local 3-axis), both frames at -35 MPa through *INITIAL CONDITIONS,
TYPE=STRESS, confinement with a constant amplitude. Units mm, N, MPa, s.
"""
import math
import os
import re

PROPS = """*USER MATERIAL, CONSTANTS=20, UNSYMM
** phi, lambda_hard, muT_hard, muL_hard, a_hard, b_hard, M_hard, lambda_p_hard
 0.5, 2900., 18000., 13000., 4100., 6900., 1.46, 0.00013
** c1, c2, c3, pc0_hard, eta_hard, lambda_soft, mu_soft, M_soft
 0.73, -0.20, 0.40, 2.0, 1.3E13, 4600., 3100., 1.46
** lambda_p_soft, pc0_soft, eta_soft, tol (0: no step control; these decks take fixed or host-chosen increments)
 0.0026, 35.0, 1.3E10, 0.
*DEPVAR
 36
"""

# Local 1 and 2 axes of *ORIENTATION (local 3 = 1 x 2 is the bedding normal), per bedding angle.
# theta = 0: the global axes (normal = z, the load axis). theta = 90: local 1 = y, local 2 = z,
# so the normal is x, as in docs/umat.md.
ORIENTATION = {0: ((1., 0., 0.), (0., 1., 0.)), 90: ((0., 1., 0.), (0., 0., 1.))}

# Fixed increments of the one-element runs: (increment, step period) per *STEP. Steps 1-3: hold the
# confinement 1e6 s (the hard frame compacts, pc_h 2 -> ~28 MPa); step 4: ramp the deviator to
# 40 MPa in 1 s; steps 5-8: creep 36000 s. Increments grow where the rates fall.
HOLD = [(100., 1000.), (9900., 99000.), (1e5, 9e5)]
RAMP = [(0.25, 1.)]
CREEP = [(10., 100.), (90., 900.), (900., 9000.), (2000., 26000.)]
# The same for the conventions probe (prescribed strain with shear, 100 s).
PROBE = [(25., 100.)]

# Tight Newton tolerances (residual and correction ratios 1e-12 instead of 0.005/0.01) and patient
# iteration counts: CalculiX symmetrises DDSDDE, so its Newton converges linearly (docs/calculix.md).
CONTROLS = """*CONTROLS, PARAMETERS=FIELD
 1.E-12, 1.E-12, 0., 0., 1.E-12, 1.E-5, 1.E-3, 1.E-13
*CONTROLS, PARAMETERS=TIME INCREMENTATION
 30, 40, 9, 60, 60, 4, 0, 5
"""

CUBE_NODES = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
# Side of the one-element cube (mm). CalculiX sets an equilibrium residual below 1e-6 force units to
# zero and then declares convergence (nonlingeo.c), whatever *CONTROLS says: with a 1 mm cube (nodal
# forces ~9 N) that leaves stress errors of ~1e-7 relative; with 100 mm (~9e4 N), ~1e-11.
SIDE = 100

# General strain of the conventions probe (tensor components, order 11, 22, 33, 12, 13, 23) and its
# oblique bedding: normal n = (sin 30 cos 20, sin 30 sin 20, cos 30).
PROBE_STRAIN = (-4.0e-4, 1.5e-4, -9.0e-4, 2.0e-4, -3.0e-4, 1.0e-4)


def probe_axes():
    th, az = math.radians(30.), math.radians(20.)
    n = (math.sin(th) * math.cos(az), math.sin(th) * math.sin(az), math.cos(th))
    a = (math.cos(th) * math.cos(az), math.cos(th) * math.sin(az), -math.sin(th))   # unit, normal to n
    return a, (n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0])  # b = n x a


# CalculiX removes the blanks of a data line, splits it at the commas and reads each real from the first
# FIELD characters of its field with the Fortran edit descriptor f20.0 (nodes.f, e.g. `read(textpart(2)
# (1:20),'(f20.0)') co(1,i)`); the rest of a longer field is dropped without a word. 15 significant digits
# do not always fit: -3.11060286983428e-15 has 21 characters and was read as -0.311 (issue 13).
FIELD = 20
_FORTRAN_REAL = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))(?:[eEdDqQ]([+-]?\d+)|([+-]\d+))?$")


def fortran_real(text, width=FIELD):
    """The value an f<width>.0 read of `text` gives, as CalculiX reads a field: its first `width`
    characters, blanks removed; an empty field reads as 0 (Fortran 2008, 13.7.2.3.2: F editing)."""
    field = text[:width].replace(" ", "")
    if not field:
        return 0.0
    m = _FORTRAN_REAL.match(field)
    if not m:
        raise ValueError(f"'{field}' is not a Fortran real (F editing)")
    return float(m.group(1) + "e" + (m.group(2) or m.group(3) or "0"))


def fmt(v, width=FIELD, digits=15):
    """`v` with the most significant digits, up to `digits`, whose text fits a `width`-character field,
    checked to read back (fortran_real) to `v` within the rounding of the digits written. Raises
    ValueError naming the value and the field where no text fits or the read-back differs."""
    v = float(v)
    if not math.isfinite(v):
        raise ValueError(f"make_inputs: cannot write {v!r} into an Abaqus/CalculiX input: expected a finite number")
    for n in range(digits, 0, -1):
        text = f"{v:.{n}g}"
        text = text if any(c in text for c in ".e") else text + "."
        if len(text) <= width:
            break
    else:
        raise ValueError(f"make_inputs: {v!r} does not fit a {width}-character field (CalculiX reads f{width}.0) "
                         f"even with 1 significant digit ('{text}')")
    back = fortran_real(text, width)
    # Rounding to n significant digits moves v by at most half a unit of its n-th digit, 0.5 10^(1-n) |v|;
    # the decimal-to-binary conversion adds at most one rounding of a double.
    if not abs(back - v) <= (0.5 * 10.0 ** (1 - n) + 2.0 ** -52) * abs(v):
        raise ValueError(f"make_inputs: {v!r} written as '{text}' reads back as {back!r} from a {width}-character "
                         f"field (CalculiX reads f{width}.0): expected {v!r} to {n} significant digits")
    return text


def orientation(a, b):
    return ("*ORIENTATION, NAME=BEDDING, SYSTEM=RECTANGULAR\n " + ", ".join(fmt(x) for x in a + b) + "\n")


def material(axes, abaqus=False):
    # Abaqus' *SOLID SECTION takes a data line (empty for solid elements, as Abaqus/CAE writes it).
    section = "*SOLID SECTION, ELSET=EALL, MATERIAL=ABAQUS_WOODFORD, ORIENTATION=BEDDING\n" + (",\n" if abaqus else "")
    return orientation(*axes) + section + "*MATERIAL, NAME=ABAQUS_WOODFORD\n" + PROPS


def initial_stress(elements, points):
    lines = "".join(f" {e}, {i}, -35., -35., -35., 0., 0., 0.\n" for e in elements for i in range(1, points + 1))
    return "** both frames start at -35 MPa: the UMAT copies STRESS into both on its first call\n" \
           "*INITIAL CONDITIONS, TYPE=STRESS\n" + lines


# Abaqus reads the initial stress by element set: one line for all elements and points.
ABAQUS_INITIAL_STRESS = ("** both frames start at -35 MPa: the UMAT copies STRESS into both on its first call\n"
                         "*INITIAL CONDITIONS, TYPE=STRESS\n EALL, -35., -35., -35., 0., 0., 0.\n")
# Abaqus output: the .dat (integration points; S and E in the orientation's axes, SDV as stored) and the
# output database.
ABAQUS_OUTPUT = ("*EL PRINT, ELSET=EALL\n S, E, SDV\n*NODE PRINT, NSET=NALL\n U\n"
                 "*OUTPUT, FIELD\n*ELEMENT OUTPUT, ELSET=EALL\n S, E, SDV\n*NODE OUTPUT\n U\n")


def steps(plan, output, controls=CONTROLS):
    """One *STEP with fixed increments per (increment, period, loads); *CONTROLS once, in the first."""
    return "".join(f"*STEP, INC=100000\n*STATIC, DIRECT\n {fmt(dt)}, {fmt(period)}\n" + (controls if k == 0 else "")
                   + loads + output + "*END STEP\n" for k, (dt, period, loads) in enumerate(plan))


def one_element(theta, abaqus=False):
    nodes = "".join(f" {i}, {SIDE * x}., {SIDE * y}., {SIDE * z}.\n" for i, (x, y, z) in enumerate(CUBE_NODES, 1))
    out = ("*EL PRINT, ELSET=EALL, GLOBAL=YES\n S, E, SDV\n*NODE PRINT, NSET=NALL\n U\n"
           "*NODE FILE\n U\n*EL FILE\n S, E, SDV\n")
    conf = "*DSLOAD, AMPLITUDE=CONST\n SIDES, P, 35.\n TOP, P, 35.\n"
    dev = "** the top pressure ramps from 35 to 75 MPa over this step (sigma_d = 40 MPa)\n*DSLOAD\n TOP, P, 75.\n"
    plan = [(dt, T, conf if k == 0 else "") for k, (dt, T) in enumerate(HOLD)]
    plan += [(dt, T, dev) for dt, T in RAMP]
    plan += [(dt, T, "") for dt, T in CREEP]
    if abaqus:
        head = f"""** Abaqus/Standard: triaxial creep of one C3D8 element (cube of side {SIDE} mm), theta = {theta} deg,
** Cam-Clay IX UMAT (abaqus job=... user=camclay9_umat_abaqus.for; docs/umat.md).
** Both frames start at -35 MPa; confinement 35 MPa held 1e6 s; deviator 40 MPa ramped in 1 s; creep 36000 s.
** Homogeneous: pressure on the faces x = 1, y = 1, z = 1, rollers on x = 0, y = 0, z = 0. Fixed increments.
** The CalculiX deck of the same test is triaxial_c3d8_theta{theta}.inp; the keywords are checked in KEYWORDS.md.
** Written by tools/calculix/make_inputs.py. Units mm, N, MPa, s."""
        init, stepping = ABAQUS_INITIAL_STRESS, steps(plan, ABAQUS_OUTPUT, controls="")
    else:
        head = f"""** Triaxial creep of one C3D8 element (cube of side {SIDE} mm), theta = {theta} deg: Cam-Clay IX UMAT.
** Both frames start at -35 MPa; confinement 35 MPa held 1e6 s; deviator 40 MPa ramped in 1 s; creep 36000 s.
** Homogeneous: pressure on the faces x = 1, y = 1, z = 1, rollers on x = 0, y = 0, z = 0.
** Fixed increments and tight *CONTROLS so that tests/calculix can replay the same increments at one point.
** Written by tools/calculix/make_inputs.py. Units mm, N, MPa, s."""
        init, stepping = initial_stress([1], 8), steps(plan, out)
    return f"""{head}
*HEADING
Cam-Clay IX triaxial creep, one C3D8, theta = {theta}
*NODE, NSET=NALL
{nodes}*ELEMENT, TYPE=C3D8, ELSET=EALL
 1, 1, 2, 3, 4, 5, 6, 7, 8
*NSET, NSET=X0
 1, 4, 5, 8
*NSET, NSET=Y0
 1, 2, 5, 6
*NSET, NSET=Z0
 1, 2, 3, 4
*SURFACE, NAME=SIDES, TYPE=ELEMENT
 1, S4
 1, S5
*SURFACE, NAME=TOP, TYPE=ELEMENT
 1, S2
{material(ORIENTATION[theta], abaqus)}*AMPLITUDE, NAME=CONST
 0., 1., 1.E10, 1.
*BOUNDARY
 X0, 1
 Y0, 2
 Z0, 3
{init}{stepping}"""


def probe():
    e = PROBE_STRAIN
    E = [[e[0], e[3], e[4]], [e[3], e[1], e[5]], [e[4], e[5], e[2]]]
    nodes = "".join(f" {i}, {x}., {y}., {z}.\n" for i, (x, y, z) in enumerate(CUBE_NODES, 1))
    bcs = "*BOUNDARY\n"
    for i, x in enumerate(CUBE_NODES, 1):
        for d in range(3):
            bcs += f" {i}, {d + 1}, {d + 1}, {fmt(sum(E[d][j] * x[j] for j in range(3)))}\n"
    out = ("*EL PRINT, ELSET=EALL\n S, E\n*EL PRINT, ELSET=EALL, GLOBAL=YES\n S, E, SDV\n"
           "*EL FILE\n S, E, SDV\n")
    return f"""** Conventions probe: one C3D8 (unit cube) whose every node follows u = E x, a general strain with
** shear ({', '.join(fmt(v) for v in e)}; tensor components 11 22 33 12 13 23), bedding normal oblique
** (30 deg from z, azimuth 20 deg) through *ORIENTATION. Shows the order of the shear components in .dat
** and .frd, local versus global output, the strain measure, and the rotation of STRESS and DDSDDE.
** Written by tools/calculix/make_inputs.py. Units mm, N, MPa, s.
*HEADING
Cam-Clay IX conventions probe, one C3D8, prescribed general strain
*NODE, NSET=NALL
{nodes}*ELEMENT, TYPE=C3D8, ELSET=EALL
 1, 1, 2, 3, 4, 5, 6, 7, 8
{material(probe_axes())}{initial_stress([1], 8)}{steps([(dt, T, bcs) for dt, T in PROBE], out)}"""


# The cylinder of the triaxial scene (input/triaxial.yaml): diameter 25.4 mm, height 50.8 mm,
# uniform phi = 0.5 so that it stays homogeneous and can be compared with one point. Coarse O-grid:
# a core square of CORE x CORE elements, one ring out to the circle, LAYERS element layers.
RADIUS, HEIGHT, CORE, LAYERS = 12.7, 50.8, 4, 4
# Automatic incrementation (initial, period, minimum, maximum) per phase.
CYL_STEPS = [(10., 1e6, 1., 2e5), (0.25, 1., 1e-6, 0.25), (1., 36000., 0.1, 2000.)]


def disk():
    """Nodes (x, y) and counterclockwise quads of the O-grid disk."""
    a, n = 0.5 * RADIUS, CORE
    xy = [(a * (2 * i / n - 1), a * (2 * j / n - 1)) for j in range(n + 1) for i in range(n + 1)]
    quads = [(j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i)
             for j in range(n) for i in range(n)]
    # Core perimeter, counterclockwise from (a, -a): each of its nodes gets a partner on the circle.
    ring = [(n, j) for j in range(n)] + [(n - i, n) for i in range(n)] + \
           [(0, n - j) for j in range(n)] + [(i, 0) for i in range(n)]
    inner = [j * (n + 1) + i for i, j in ring]
    outer = []
    for k in inner:
        x, y = xy[k]
        r = math.hypot(x, y)
        outer.append(len(xy))
        xy.append((RADIUS * x / r, RADIUS * y / r))
    m = len(inner)
    quads += [(inner[k], outer[k], outer[(k + 1) % m], inner[(k + 1) % m]) for k in range(m)]
    return xy, quads, len(quads) - m


CYL_INIT = "triaxial_cylinder_initial_stress.inc"


def ids_lines(ids, per_line=12):
    """Node or element numbers, a few per line (CalculiX reads at most 132 characters a line)."""
    ids = [str(i) for i in ids]
    return "".join(" " + ", ".join(ids[k:k + per_line]) + "\n" for k in range(0, len(ids), per_line))


def cylinder(theta, abaqus=False):
    xy, quads, n_core = disk()
    per = len(xy)
    node = lambda k, layer: layer * per + k + 1                       # noqa: E731
    nodes = "".join(f" {node(k, l)}, {fmt(x)}, {fmt(y)}, {fmt(HEIGHT * l / LAYERS)}\n"
                    for l in range(LAYERS + 1) for k, (x, y) in enumerate(xy))
    elems, sides, top = "", "", ""
    e = 0
    for l in range(LAYERS):
        for q, quad in enumerate(quads):
            e += 1
            ids = [node(k, l) for k in quad] + [node(k, l + 1) for k in quad]
            elems += f" {e}, " + ", ".join(str(i) for i in ids) + "\n"
            if q >= n_core:
                sides += f" {e}, S4\n"                                  # nodes 2, 3 lie on the circle
            if l == LAYERS - 1:
                top += f" {e}, S2\n"
    centre = node(xy.index((0.0, 0.0)), 0)
    on_x = node(min(range(per), key=lambda k: math.hypot(xy[k][0] - RADIUS, xy[k][1])), 0)
    bottom = ids_lines(node(k, 0) for k in range(per))
    tops = ids_lines(node(k, LAYERS) for k in range(per))
    mid = (LAYERS // 2) * len(quads) + 1                                 # a core element at mid-height
    conf = "*DSLOAD, AMPLITUDE=CONST\n OUTER, P, 35.\n TOP, P, 35.\n"
    dev = "** the top pressure ramps from 35 to 75 MPa over this step (sigma_d = 40 MPa)\n*DSLOAD\n TOP, P, 75.\n"
    out = "*NODE PRINT, NSET=NTOP\n U\n*EL PRINT, ELSET=EMID, GLOBAL=YES\n S, SDV\n"
    if abaqus:
        out = ("*NODE PRINT, NSET=NTOP\n U\n*EL PRINT, ELSET=EMID\n S, SDV\n"
               "*OUTPUT, FIELD\n*ELEMENT OUTPUT, ELSET=EALL\n S, E, SDV\n*NODE OUTPUT\n U\n")
    text = ""
    for k, ((dt, period, tmin, tmax), loads) in enumerate(zip(CYL_STEPS, [conf, dev, ""])):
        text += (f"*STEP, INC=100000\n*STATIC\n {fmt(dt)}, {fmt(period)}, {fmt(tmin)}, {fmt(tmax)}\n"
                 + (CONTROLS if k == 0 and not abaqus else "") + loads + out + "*END STEP\n")
    if abaqus:
        head = f"""** Abaqus/Standard: triaxial creep of a cylinder (diameter {2 * RADIUS} mm, height {HEIGHT} mm), theta = {theta} deg,
** C3D8, {e} elements, Cam-Clay IX UMAT (abaqus job=... user=camclay9_umat_abaqus.for; docs/umat.md), uniform
** phi = 0.5 (the scene draws phi per element; uniform here so that the cylinder stays homogeneous and
** matches one material point). Both frames start at -35 MPa; confinement 35 MPa held 1e6 s; deviator
** 40 MPa ramped in 1 s; creep 36000 s. Bottom on rollers, centre node pinned, one node on the x axis
** held in y. Automatic incrementation (Abaqus' default controls).
** The CalculiX deck of the same test is triaxial_cylinder_theta{theta}.inp; the keywords are checked in KEYWORDS.md.
** Written by tools/calculix/make_inputs.py. Units mm, N, MPa, s."""
        init = ABAQUS_INITIAL_STRESS
    else:
        head = f"""** Triaxial creep of a cylinder (diameter {2 * RADIUS} mm, height {HEIGHT} mm), theta = {theta} deg, C3D8,
** {e} elements: Cam-Clay IX UMAT, uniform phi = 0.5 (the scene draws phi per element; uniform here so
** that the cylinder stays homogeneous and matches one material point). Both frames start at -35 MPa;
** confinement 35 MPa held 1e6 s; deviator 40 MPa ramped in 1 s; creep 36000 s. Bottom on rollers,
** centre node pinned, one node on the x axis held in y. Automatic incrementation.
** Written by tools/calculix/make_inputs.py. Units mm, N, MPa, s."""
        init = ("** both frames start at -35 MPa (one line per element and integration point, in a file of its own)\n"
                f"*INITIAL CONDITIONS, TYPE=STRESS\n*INCLUDE, INPUT={CYL_INIT}\n")
    return f"""{head}
*HEADING
Cam-Clay IX triaxial creep, cylinder, theta = {theta}
*NODE, NSET=NALL
{nodes}*ELEMENT, TYPE=C3D8, ELSET=EALL
{elems}*ELSET, ELSET=EMID
 {mid}
*NSET, NSET=NBOTTOM
{bottom}*NSET, NSET=NTOP
{tops}*SURFACE, NAME=OUTER, TYPE=ELEMENT
{sides}*SURFACE, NAME=TOP, TYPE=ELEMENT
{top}{material(ORIENTATION[theta], abaqus)}*AMPLITUDE, NAME=CONST
 0., 1., 1.E10, 1.
*BOUNDARY
 NBOTTOM, 3
 {centre}, 1, 2
 {on_x}, 2
{init}{text}"""


# The Abaqus/Standard decks (input/abaqus/KEYWORDS.md checks their keywords line by line).
ABAQUS_DECKS = {f"triaxial_c3d8_theta{t}_abaqus.inp": (one_element, t) for t in (0, 90)}
ABAQUS_DECKS.update({f"triaxial_cylinder_theta{t}_abaqus.inp": (cylinder, t) for t in (0, 90)})


def write(outdir):
    os.makedirs(outdir, exist_ok=True)
    files = {"triaxial_c3d8_theta0.inp": one_element(0), "triaxial_c3d8_theta90.inp": one_element(90),
             "conventions_c3d8.inp": probe(), "triaxial_cylinder_theta0.inp": cylinder(0),
             "triaxial_cylinder_theta90.inp": cylinder(90),
             CYL_INIT: initial_stress(range(1, LAYERS * len(disk()[1]) + 1), 8).split("TYPE=STRESS\n")[1]}
    files.update({name: make(theta, abaqus=True) for name, (make, theta) in ABAQUS_DECKS.items()})
    for name, text in files.items():
        with open(os.path.join(outdir, name), "w") as f:
            f.write(text)
    return sorted(files)

