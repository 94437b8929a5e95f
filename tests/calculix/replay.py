"""One material point driven through CalculiX's increments, and readers of what CalculiX wrote.

The point calls the project's UMAT (libcamclay9.so of the build, through ctypes) with the bedding normal
in PROPS 21-23 and the global frame, where CalculiX instead passes the material frame of its
*ORIENTATION and 20 constants. Both sides are then compared per increment (test_calculix.py).
"""
import ctypes
import os

import numpy as np

c_int_p = ctypes.POINTER(ctypes.c_int)
c_dbl_p = ctypes.POINTER(ctypes.c_double)
VOIGT = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]   # Abaqus order 11, 22, 33, 12, 13, 23


def _built(env, names, what):
    """The file named by the environment variable env (set by CTest), else the first of names (relative to
    CAMCLAY9_BUILD, by default build/, then build-umat/) that exists; an error naming them otherwise."""
    if os.environ.get(env):
        return os.environ[env]
    repo = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    builds = [os.environ["CAMCLAY9_BUILD"]] if os.environ.get("CAMCLAY9_BUILD") else \
        [os.path.join(repo, "build"), os.path.join(repo, "build-umat")]
    tried = [os.path.join(b, n) for b in builds for n in names]
    for path in tried:
        if os.path.exists(path):
            return path
    raise FileNotFoundError(f"{what} not found (set {env}, or build the project): tried " + ", ".join(tried))


def umat_object():
    """camclay9_umat.o of the full build (build/umat/) or of a UMAT-only build (build-umat/)."""
    return _built("CAMCLAY9_UMAT_OBJECT", ["umat/camclay9_umat.o", "camclay9_umat.o"], "camclay9_umat.o")


def load_umat(build=None):
    """umat_ of libcamclay9.so (CAMCLAY9_UMAT_LIBRARY, or found like umat_object)."""
    path = _built("CAMCLAY9_UMAT_LIBRARY", ["umat/libcamclay9.so", "libcamclay9.so"], "libcamclay9.so")
    return ctypes.CDLL(path).umat_


def _d(a):
    return a.ctypes.data_as(c_dbl_p)


class Point:
    """A material point with the state CalculiX starts from: STRESS given, STATEV zero."""

    def __init__(self, umat, props, stress0, nstatv=36):
        self.umat = umat
        self.props = np.asarray(props, dtype=float)
        self.stress = np.array(stress0, dtype=float)
        self.statev = np.zeros(nstatv)
        self.stran = np.zeros(6)
        self.calls = 0

    def trial(self, dstran, time, dtime, kinc=1, jstep=1):
        """Call the UMAT on copies of the state; return (stress, statev, ddsdde, pnewdt)."""
        stress, statev = self.stress.copy(), self.statev.copy()
        ddsdde = np.zeros((6, 6), order="F")
        scal = [ctypes.c_double(0.0) for _ in range(6)]          # sse, spd, scd, rpl, drpldt, temp
        ddsddt, drplde = np.zeros(6), np.zeros(6)
        dstran = np.array(dstran, dtype=float)
        t = np.array(time, dtype=float)
        zero = np.zeros(9)
        drot, dfgrd = np.eye(3, order="F"), np.eye(3, order="F")
        pnewdt = ctypes.c_double(1.0)
        i = ctypes.c_int
        cmname = ctypes.create_string_buffer(b"_WOODFORD".ljust(80), 80)
        self.umat(_d(stress), _d(statev), _d(ddsdde), ctypes.byref(scal[0]), ctypes.byref(scal[1]),
                  ctypes.byref(scal[2]), ctypes.byref(scal[3]), _d(ddsddt), _d(drplde), ctypes.byref(scal[4]),
                  _d(self.stran), _d(dstran), _d(t), ctypes.byref(ctypes.c_double(dtime)),
                  ctypes.byref(scal[5]), ctypes.byref(ctypes.c_double(0.0)), _d(zero), _d(zero), cmname,
                  ctypes.byref(i(3)), ctypes.byref(i(3)), ctypes.byref(i(6)), ctypes.byref(i(len(statev))),
                  _d(self.props), ctypes.byref(i(len(self.props))), _d(zero), _d(drot), ctypes.byref(pnewdt),
                  ctypes.byref(ctypes.c_double(1.0)), _d(dfgrd), _d(dfgrd), ctypes.byref(i(1)),
                  ctypes.byref(i(1)), ctypes.byref(i(1)), ctypes.byref(i(1)),
                  (ctypes.c_int * 4)(jstep, 1, 0, 0), ctypes.byref(i(kinc)), ctypes.c_ulong(80))
        self.calls += 1
        return stress, statev, np.array(ddsdde), pnewdt.value

    def commit(self, dstran, stress, statev):
        self.stran = self.stran + dstran
        self.stress, self.statev = stress, statev

    def strain_step(self, dstran, time, dtime):
        stress, statev, _, _ = self.trial(dstran, time, dtime)
        self.commit(np.asarray(dstran, dtype=float), stress, statev)

    def stress_step(self, target, time, dtime, guess=None, rtol=1e-13, maxit=40):
        """Find the strain increment whose stress is `target` (all six components controlled):
        Newton with the UMAT's own (unsymmetric, consistent) tangent. Returns the iteration count."""
        target = np.asarray(target, dtype=float)
        de = np.zeros(6) if guess is None else np.array(guess, dtype=float)
        scale = np.abs(target).max()
        for it in range(1, maxit + 1):
            stress, statev, d, _ = self.trial(de, time, dtime)
            r = stress - target
            if np.abs(r).max() <= rtol * scale:
                self.commit(de, stress, statev)
                return it
            de = de - np.linalg.solve(d, r)
        raise RuntimeError(f"stress-controlled point did not converge at t = {time[1] + dtime}")


def rotation(a, b):
    """Columns: the local axes of *ORIENTATION, SYSTEM=RECTANGULAR with points a and b (global coords)."""
    e1 = np.asarray(a, float) / np.linalg.norm(a)
    e3 = np.cross(e1, b)
    e3 /= np.linalg.norm(e3)
    return np.column_stack([e1, np.cross(e3, e1), e3])


def to_tensor(v, engineering=False):
    t = np.zeros((3, 3))
    for k, (i, j) in enumerate(VOIGT):
        t[i, j] = t[j, i] = v[k] / (2.0 if engineering and k > 2 else 1.0)
    return t


def to_voigt(t, engineering=False):
    return np.array([t[i, j] * (2.0 if engineering and k > 2 else 1.0) for k, (i, j) in enumerate(VOIGT)])


def local_to_global(v, q, engineering=False):
    return to_voigt(q @ to_tensor(v, engineering) @ q.T, engineering)


def statev_to_global(sv, q):
    """Tensor slots of STATEV (docs/umat.md) from the material frame to the global one."""
    out = np.array(sv, dtype=float)
    for first, eng in ((0, False), (6, True), (13, False), (19, True), (26, True)):
        out[first:first + 6] = local_to_global(sv[first:first + 6], q, eng)
    return out


def read_trace(path):
    """umat_trace.f90's log: header (cmname, sizes, props) and one record per call."""
    calls = []
    with open(path) as f:
        head = f.readline().split("=", 1)[1]
        cmname, sizes = head.rsplit("|", 1)
        ndi, nshr, ntens, nstatv, nprops = (int(x) for x in sizes.split())
        props = np.array([float(x) for x in f.readline().split()[2:]])
        for line in f:
            w = line.split()
            v = np.array([float(x) for x in w[13:]])
            n = ntens
            calls.append(dict(jstep=int(w[0]), kinc=int(w[4]), noel=int(w[5]), npt=int(w[6]),
                              time=(float(w[7]), float(w[8])), dtime=float(w[9]),
                              pnewdt_in=float(w[10]), pnewdt_out=float(w[11]), drot_identity=w[12] == "T",
                              asym=v[0], stran=v[1:1 + n], dstran=v[1 + n:1 + 2 * n],
                              stress_in=v[1 + 2 * n:1 + 3 * n], stress=v[1 + 3 * n:1 + 4 * n],
                              statev_in=v[1 + 4 * n:1 + 4 * n + nstatv], statev=v[1 + 4 * n + nstatv:]))
    return dict(cmname=cmname, ndi=ndi, nshr=nshr, ntens=ntens, nstatv=nstatv, nprops=nprops, props=props,
                calls=calls)


def converged(calls):
    """The last call per (step, increment, element, point): the state CalculiX keeps."""
    last = {}
    for c in calls:
        last[(c["jstep"], c["kinc"], c["noel"], c["npt"])] = c
    return last


def read_dat(path):
    """*EL PRINT / *NODE PRINT blocks of a CalculiX .dat: list of (title, time, rows)."""
    blocks = []
    with open(path) as f:
        for line in f:
            if " for set " in line and "time" in line:
                blocks.append((line.split(" for set ")[0].strip(), float(line.split()[-1]), []))
            elif blocks and line.strip():
                try:
                    blocks[-1][2].append([float(x) for x in line.split()[:99]])
                except ValueError:     # the orientation name that follows local values
                    blocks[-1][2].append([float(x) for x in line.split()[:-1]])
    return blocks


def read_props(inp):
    """The *USER MATERIAL constants of an input file (comment lines skipped)."""
    values, inside = [], False
    with open(inp) as f:
        for line in f:
            s = line.strip()
            if s.startswith("**"):
                continue
            if s.upper().startswith("*USER MATERIAL"):
                inside = True
            elif s.startswith("*"):
                inside = False
            elif inside and s:
                values += [float(x) for x in s.split(",") if x.strip()]
    return np.array(values)


def read_orientation(inp):
    with open(inp) as f:
        lines = f.readlines()
    for k, line in enumerate(lines):
        if line.upper().startswith("*ORIENTATION"):
            x = [float(v) for v in lines[k + 1].split(",")]
            return rotation(x[:3], x[3:6])
    return np.eye(3)
