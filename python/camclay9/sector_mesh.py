"""The indentation sector's meshes (meshes/indent_sector.geo, a 60-degree sector of the hexagonal prism under a
Berkovich tip) for tests/driver/test_sector.py and bench/indent_models_bench.py: the sector meshed by gmsh, gmsh 2.2
files read and written, and the half model x >= 0 made of three mirror images of the sector's mesh (the driver reads
format 4.1: msh41 converts).
"""
import math
import subprocess
from pathlib import Path

import numpy as np
from camclay9.launch import repo_root


def mesh_sector(out, root=None, **par):
    """meshes/indent_sector.geo of the repository `root` (default: camclay9.repo_root()) meshed with the gmsh
    parameters `par` as a gmsh 2.2 file (read by read_msh below)."""
    geo = repo_root(root) / "meshes" / "indent_sector.geo"
    args = ["gmsh", "-3", str(geo), "-format", "msh22", "-o", str(out)]
    for k, v in par.items():
        args += ["-setnumber", k, str(v)]
    subprocess.run(args, check=True, capture_output=True, timeout=600)
    return out


def msh41(path):
    """The driver reads gmsh format 4.1 only (io/gmsh_mesh.c refuses 2.x: PETSc 3.18 mislabels its physical
    groups); the 2.2 files of this module (read and written by read_msh, write_msh) converted by gmsh."""
    out = path.with_name(path.stem + "_41.msh")
    subprocess.run(["gmsh", str(path), "-0", "-format", "msh41", "-o", str(out)], check=True, capture_output=True, timeout=600)
    return out


def read_msh(path):
    """gmsh 2.2 (ASCII): physical names, nodes (id -> row), elements (type, physical tag, node ids)."""
    lines = Path(path).read_text().split("\n")
    i, names, ids, xyz, elems = 0, {}, [], [], []
    while i < len(lines):
        if lines[i] == "$PhysicalNames":
            for j in range(int(lines[i + 1])):
                d, t, n = lines[i + 2 + j].split(maxsplit=2)
                names[int(t)] = (int(d), n.strip('"'))
        elif lines[i] == "$Nodes":
            for j in range(int(lines[i + 1])):
                w = lines[i + 2 + j].split()
                ids.append(int(w[0]))
                xyz.append([float(v) for v in w[1:4]])
        elif lines[i] == "$Elements":
            for j in range(int(lines[i + 1])):
                w = [int(v) for v in lines[i + 2 + j].split()]
                elems.append((w[1], w[3], w[3 + w[2]:]))
        i += 1
    return names, dict(zip(ids, range(len(ids)))), np.array(xyz), elems


def write_msh(path, groups, x, elems):
    """gmsh 2.2: groups {name: (dim, tag)}, x (nodes 1..n), elems [(type, tag, nodes)]."""
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(groups))]
    out += [f'{d} {t} "{n}"' for n, (d, t) in groups.items()] + ["$EndPhysicalNames", "$Nodes", str(len(x))]
    out += [f"{k + 1} {a:.17g} {b:.17g} {c:.17g}" for k, (a, b, c) in enumerate(x)] + ["$EndNodes", "$Elements", str(len(elems))]
    out += [f"{k + 1} {t} 2 {g} {g} " + " ".join(map(str, n)) for k, (t, g, n) in enumerate(elems)] + ["$EndElements", ""]
    Path(path).write_text("\n".join(out))


def mirrored_half(sector_msh, out):
    """The half x >= 0 of the hexagonal prism as three mirror images of the sector's mesh [30, 90] degrees: its
    reflection about the plane at 30 degrees ([-30, 30]), and that one's about the plane at -30 degrees ([-90, -30]).
    Nodes on a reflecting plane are shared; reflected elements are reordered to keep their orientation. The faces
    on the two inner planes are dropped; the vertical outer faces are grouped by plane: x0 and side_m60, side_0,
    side_60 (by the azimuth of their outward normal)."""
    names, row, x0, elems0 = read_msh(sector_msh)
    byname = {n: t for t, (d, n) in names.items()}
    x = [tuple(v) for v in x0]
    copies = [[(t, names[g][1], [row[i] for i in n]) for t, g, n in elems0]]
    for phi in (30.0, -30.0):
        m = np.array([math.sin(math.radians(phi)), -math.cos(math.radians(phi)), 0.0])  # the plane's normal
        image = {}
        new = []
        for t, g, nodes in copies[-1]:
            for i in nodes:
                if i not in image:
                    xi = np.array(x[i])
                    if abs(xi @ m) < 1e-12:
                        image[i] = i
                    else:
                        x.append(tuple(xi - 2 * (xi @ m) * m))
                        image[i] = len(x) - 1
            nn = [image[i] for i in nodes]
            if len(nn) >= 3:
                nn[0], nn[1] = nn[1], nn[0]
            new.append((t, g, nn))
        copies.append(new)
    x = np.array(x)
    groups = {"block": (3, 1), "bottom": (2, 2), "top": (2, 3), "contact": (2, 4), "x0": (2, 5), "side_m60": (2, 6),
              "side_0": (2, 7), "side_60": (2, 8), "tip": (0, 9)}
    elems = []
    for c, copy in enumerate(copies):
        for t, g, nodes in copy:
            if t == 15 and c > 0:
                continue
            if t == 2 and g in ("mirror_a", "mirror_b", "side1"):
                p = x[nodes]
                n = np.cross(p[1] - p[0], p[2] - p[0])
                n /= np.linalg.norm(n)
                d = p.mean(axis=0) @ n
                if d < 0:
                    n, d = -n, -d
                if d < 1e-9:
                    if abs(p[:, 0]).max() > 1e-12:
                        continue   # an inner plane
                    g = "x0"
                else:
                    g = {-60: "side_m60", 0: "side_0", 60: "side_60"}[round(math.degrees(math.atan2(n[1], n[0])))]
            elems.append((t, groups[g][1], [i + 1 for i in nodes]))
    assert "side1" in byname
    write_msh(out, groups, x, elems)
    return out
