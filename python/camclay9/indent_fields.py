"""Measures of a 2D indentation run's cell fields that do not hang on one cell (issue 26): region means over a
fixed rectangle of the undeformed mesh (the cells clipped to it, so the mean is exact for cell-constant fields and
does not jump as a centroid crosses the region's edge), nodal averages for maps without the cell-to-cell
checkerboard, and the checkerboard's size. Tensor fields are read through six() alone.
"""
import numpy as np

from camclay9.fields import tensor6


def six(F, name, k):
    """The (ncells, 6) cell values of tensor field `name` at output k, components 11 22 33 12 13 23 (strains with
    engineering shear), read by camclay9.fields: the one place here that knows how fields.h5 stores a tensor."""
    return tensor6(F.f, name, k)


def cell_areas(F):
    x = F.x[:, :2][F.cells]
    return 0.5 * np.abs(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]))


def _clip(poly, axis, value, keep_below):
    """Sutherland-Hodgman: the part of a polygon (list of (x, y)) on one side of the line x[axis] = value."""
    out = []
    for i, p in enumerate(poly):
        q = poly[i - 1]
        pin = p[axis] <= value if keep_below else p[axis] >= value
        qin = q[axis] <= value if keep_below else q[axis] >= value
        if pin != qin:
            t = (value - q[axis]) / (p[axis] - q[axis])
            out.append((q[0] + t * (p[0] - q[0]), q[1] + t * (p[1] - q[1])))
        if pin:
            out.append(p)
    return out


def _area(poly):
    if len(poly) < 3:
        return 0.0
    x, y = np.array(poly).T
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def clipped_areas(F, rect):
    """The area of each cell inside rect = (x0, x1, y0, y1) (undeformed coordinates)."""
    x0, x1, y0, y1 = rect
    xy = F.x[:, :2][F.cells]
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    cand = np.flatnonzero((hi[:, 0] > x0) & (lo[:, 0] < x1) & (hi[:, 1] > y0) & (lo[:, 1] < y1))
    w = np.zeros(F.cells.shape[0])
    for c in cand:
        poly = [tuple(p) for p in xy[c]]
        for axis, value, below in ((0, x0, False), (0, x1, True), (1, y0, False), (1, y1, True)):
            poly = _clip(poly, axis, value, below)
            if not poly:
                break
        w[c] = _area(poly)
    return w


def region_mean(values, weights):
    """The mean of cell values over a region, weighted by the cells' areas inside it (clipped_areas)."""
    return float(np.sum(values * weights) / np.sum(weights))


def nodal_average(F, values):
    """Cell values averaged to the vertices, each cell weighted by its area: the field drawn without the
    cell-to-cell checkerboard (linear elements under nearly isochoric flow). Nodes of no cell's corners (the
    mid-side nodes of P2 meshes in fields.h5) get NaN."""
    A = cell_areas(F)
    nv = F.x.shape[0]
    num, den = np.zeros(nv), np.zeros(nv)
    for j in range(F.cells.shape[1]):
        np.add.at(num, F.cells[:, j], A * values)
        np.add.at(den, F.cells[:, j], A)
    return np.where(den > 0, num / np.where(den > 0, den, 1.0), np.nan)   # NaN: a P2 cell's mid-side node


def checkerboard(F, values, mask):
    """The checkerboard's size: the RMS over the masked cells of (cell value - the mean of its vertices' nodal
    averages), relative to the RMS of the values there. Smooth fields give about h |grad|; a cell-to-cell
    oscillation gives its own amplitude."""
    nod = nodal_average(F, values)
    d = values - nod[F.cells].mean(axis=1)
    return float(np.sqrt(np.mean(d[mask] ** 2)) / np.sqrt(np.mean(values[mask] ** 2)))
