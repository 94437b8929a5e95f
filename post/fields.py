"""The FE driver's tensor fields, read in one place (issue 23).

fields.h5 and fields.xmf store every tensor field (stress, strain, evp_hard, evp_soft, evp) as its full 3x3
matrix, row by row: 11 12 13 21 22 23 31 32 33, strains as tensors (eps_12 = gamma_12 / 2). Every reader takes
nine components the same way (ParaView labels them XX XY XZ YX YY YZ ZX ZY ZZ, meshio gives (n, 9)), where the
six-component layout written before was read in three different orders (docs/driver.md, "Fields").

post/ works in the UMAT's Voigt order, 11 22 33 12 13 23, with engineering shear for strains (gamma_12 =
2 eps_12, as in STRAN, STATEV and history.csv): `voigt` converts a field read from the files, `tensor6` reads
one from an open fields.h5, `full` goes back (for tests that write files in the driver's layout). In 2D the
33 slot is the out-of-plane (plane strain) or hoop (axisymmetric) component and 13, 23 are zero.
"""
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
