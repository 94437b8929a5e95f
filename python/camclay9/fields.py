"""The FE driver's tensor fields, read in one place (issue 23): their layout, and fields.h5's reader.

fields.h5 and fields.xmf store every tensor field (stress, strain, evp_hard, evp_soft, evp) as its full 3x3
matrix, row by row: 11 12 13 21 22 23 31 32 33, strains as tensors (eps_12 = gamma_12 / 2). Every reader takes
nine components the same way (ParaView labels them XX XY XZ YX YY YZ ZX ZY ZZ, meshio gives (n, 9)), where the
six-component layout written before was read in three different orders (docs/driver.md, "Fields").

post/ and bench/ work in the UMAT's Voigt order, 11 22 33 12 13 23, with engineering shear for strains (gamma_12 =
2 eps_12, as in STRAN, STATEV and history.csv): `voigt` converts a field read from the files, `tensor6` reads
one from an open fields.h5, `full` goes back (for tests that write files in the driver's layout). In 2D the
33 slot is the out-of-plane (plane strain) or hoop (axisymmetric) component and 13, 23 are zero.

Reader of the FE driver's field output, fields.h5 (driver/src/fe/fe_output.c; docs/driver.md, "Output"):

  /time                      (nout, 1)   output times [s]
  /mesh/coordinates          (nnodes, dim)       the vertices, then (P2) the edge midpoints
  /mesh/cells                (ncells, n)         node numbers of each simplex: its dim + 1 vertices, then (P2)
                                                 its mid-side nodes (VTK's quadratic order)
  /fields/displacement/<k>   (nnodes, 3)  at output k (six digits); 2D padded with 0
  /fields/<name>/<k>         (ncells, 9) or (ncells,)  cell averages over the quadrature points of stress,
                             strain, evp_hard, evp_soft, evp (full 3x3 tensors, read through `voigt` below),
                             pc_hard, pc_soft, phi

Cell fields come back in the UMAT's Voigt order 11 22 33 12 13 23, strains with engineering shear (in 2D 33 is
the out-of-plane or hoop component); `cells` are the vertices of each cell (the corners of P2 cells).
Errors are SystemExit messages that name the file and the dataset.
"""
from pathlib import Path

import numpy as np

STRAINS = frozenset({"strain", "evp_hard", "evp_soft", "evp"})   # engineering shear in Voigt form
ROW_MAJOR = (0, 4, 8, 1, 2, 5)                                     # 11 22 33 12 13 23 in the 3x3 matrix, row by row
MIRROR = (0, 4, 8, 3, 6, 7)                                        # the same entries below the diagonal


def voigt(t9, strain=False):
    """(..., 9) full tensors, row by row -> (..., 6) in 11 22 33 12 13 23; strain: engineering shear (2 eps_ij)."""
    t = np.asarray(t9, dtype=float)
    if t.shape[-1] != 9:
        raise ValueError(f"expected tensors of 9 components (3x3, row by row), got {t.shape[-1]}")
    v = t[..., ROW_MAJOR].copy()
    if strain:
        v[..., 3:] *= 2.0
    return v


def full(v6, strain=False):
    """(..., 6) Voigt 11 22 33 12 13 23 (strain: engineering shear) -> (..., 9) full tensors, row by row."""
    v = np.asarray(v6, dtype=float)
    if v.shape[-1] != 6:
        raise ValueError(f"expected 6 Voigt components, got {v.shape[-1]}")
    t = np.zeros(v.shape[:-1] + (9,))
    for j, (a, b) in enumerate(zip(ROW_MAJOR, MIRROR)):
        t[..., a] = t[..., b] = v[..., j] * (0.5 if strain and j >= 3 else 1.0)
    return t


def tensor6(h5, name, k):
    """Cell field `name` at output k of an open fields.h5 (h5py.File): (ncells, 6) in 11 22 33 12 13 23 with
    engineering shear for strains, or (ncells,) for a scalar field."""
    data = h5[f"/fields/{name}/{int(k):06d}"][()]
    return voigt(data, name in STRAINS) if data.ndim == 2 and data.shape[1] == 9 else data


class _Outputs:
    """fields.h5's /fields/<name>/<k>, indexed by the output number k: (n,) or (n, ncomp) arrays."""

    def __init__(self, F, name, ncols=None):
        self.F, self.name, self.ncols = F, name, ncols

    def __getitem__(self, k):
        k = int(k) % self.F.times.size
        ds = self.F.dataset(f"/fields/{self.name}/{k:06d}")
        return ds[:, :self.ncols] if self.ncols else tensor6(self.F.f, self.name, k)


class Fields:
    """fields.h5 of a run, read lazily one output (or one cell) at a time; the output times are /time."""

    def __init__(self, run):
        import h5py
        run = Path(run)
        self.h5path = run / "fields.h5"
        if not self.h5path.is_file():
            raise SystemExit(f"{self.h5path}: no such file (the driver's field output)")
        try:
            self.f = h5py.File(self.h5path, "r")
        except OSError as err:
            raise SystemExit(f"{self.h5path}: cannot read as HDF5: {err}") from None
        self.times = np.ravel(self.dataset("/time")[()])
        if self.times.size == 0:
            raise SystemExit(f"{self.h5path}: /time is empty (no output was written)")
        self.x = self.dataset("/mesh/coordinates")[()]
        nodes = self.dataset("/mesh/cells")[()].astype(np.int64)
        nv, self.dim = self.x.shape
        if nodes.ndim != 2 or nodes.shape[1] not in ((4, 10) if self.dim == 3 else (3, 6)) or nodes.min() < 0 \
                or nodes.max() >= nv:
            raise SystemExit(f"{self.h5path}: /mesh/cells has shape {nodes.shape} and node numbers "
                             f"{nodes.min()}..{nodes.max()}: expected simplices (n x {self.dim + 1}, or with their "
                             f"mid-side nodes) of the {nv} nodes")
        self.cells = nodes[:, :self.dim + 1]                  # the corners (a P2 cell's mid-side nodes follow)
        self.u = _Outputs(self, "displacement", self.dim)     # stored with 3 components, 2D padded with 0
        for k in (0, self.times.size - 1):
            if self.u[k].shape != (nv, self.dim):
                raise SystemExit(f"{self.h5path}: /fields/displacement/{k:06d} has shape {self.u[k].shape}, "
                                 f"expected ({nv}, 3)")
        self.centroids = self.x[self.cells].mean(axis=1)
        self.extent = float(np.max(np.ptp(self.x, axis=0)))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.f.close()

    def dataset(self, name):
        if name not in self.f:
            raise SystemExit(f"{self.h5path}: dataset '{name}' is missing")
        return self.f[name]

    def cell_outputs(self, name):
        if f"/fields/{name}" not in self.f:
            have = sorted(k for k in self.f["/fields"].keys() if k != "displacement") if "/fields" in self.f else []
            raise SystemExit(f"{self.h5path}: dataset '/fields/{name}' is missing (cell fields here: "
                             f"{', '.join(have) or 'none'}; a UMAT without viscoplastic strain, e.g. the elastic "
                             f"one, writes none)")
        nt, nc = self.times.size, self.cells.shape[0]
        if len(self.f[f"/fields/{name}"]) != nt:
            raise SystemExit(f"{self.h5path}: /fields/{name} has {len(self.f[f'/fields/{name}'])} outputs, "
                             f"/time has {nt}")
        first = self.f[f"/fields/{name}/000000"]
        if first.shape[0] != nc:
            raise SystemExit(f"{self.h5path}: /fields/{name}/000000 has shape {first.shape}, expected ({nc}, ...)")
        return _Outputs(self, name)

    def cell(self, name, k):
        """Cell values of field `name` at output k: (ncells, 6) or (ncells,)."""
        return self.cell_outputs(name)[k]

    def cell_history(self, name, c):
        """Field `name` of cell c at every output: (ntimes, 6) or (ntimes,)."""
        self.cell_outputs(name)
        rows = np.array([self.f[f"/fields/{name}/{k:06d}"][c] for k in range(self.times.size)])
        return voigt(rows, name in STRAINS) if rows.ndim == 2 and rows.shape[1] == 9 else rows

    def nearest(self, t, lo=-np.inf, hi=np.inf):
        """Index of the output nearest to time t among the outputs in [lo, hi] (a tolerance included)."""
        tol = 1e-9 * max(1.0, float(np.max(np.abs(self.times))))
        idx = np.flatnonzero((self.times >= lo - tol) & (self.times <= hi + tol))
        if idx.size == 0:
            raise SystemExit(f"{self.h5path}: no output time in [{lo:g}, {hi:g}] s "
                             f"(outputs from {self.times[0]:g} to {self.times[-1]:g} s)")
        return int(idx[np.argmin(np.abs(self.times[idx] - t))])

    def require_2d(self, what):
        if self.dim != 2:
            raise SystemExit(f"{self.h5path}: {what} needs a 2D run (plane strain or axisymmetric); this mesh is {self.dim}D")


# ------------------------------------------------------------------ tensor measures (Voigt 11 22 33 12 13 23)
def tensor_norm(v, engineering):
    """Frobenius norm of (..., 6) Voigt tensors; `engineering`: the shear entries are engineering (2 x tensor)."""
    v = np.asarray(v, float)
    shear = v[..., 3:] * (0.5 if engineering else 1.0)
    return np.sqrt(np.sum(v[..., :3] ** 2, axis=-1) + 2.0 * np.sum(shear ** 2, axis=-1))


def trace(v):
    return np.sum(np.asarray(v, float)[..., :3], axis=-1)


def dev_norm(v, engineering):
    """Frobenius norm of the deviatoric part."""
    d = np.array(v, float)
    d[..., :3] -= trace(v)[..., None] / 3.0
    return tensor_norm(d, engineering)
