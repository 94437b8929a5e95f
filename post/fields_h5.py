"""Reader of the FE driver's field output, fields.h5 (driver/src/fe/fe_output.c; docs/driver.md, "Output"):

  /time                      (nout, 1)   output times [s]
  /mesh/coordinates          (nnodes, dim)       the vertices, then (P2) the edge midpoints
  /mesh/cells                (ncells, n)         node numbers of each simplex: its dim + 1 vertices, then (P2)
                                                 its mid-side nodes (VTK's quadratic order)
  /fields/displacement/<k>   (nnodes, 3)  at output k (six digits); 2D padded with 0
  /fields/<name>/<k>         (ncells, 9) or (ncells,)  cell averages over the quadrature points of stress,
                             strain, evp_hard, evp_soft, evp (full 3x3 tensors, read through post/fields.py),
                             pc_hard, pc_soft, phi

Cell fields come back in the UMAT's Voigt order 11 22 33 12 13 23, strains with engineering shear (in 2D 33 is
the out-of-plane or hoop component); `cells` are the vertices of each cell (the corners of P2 cells).
Errors are SystemExit messages that name the file and the dataset.
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fields import STRAINS, tensor6, voigt  # noqa: E402


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
