"""The mesh ladders of the 3D indentation scenes (bench/indent_convergence_bench.py runs them,
bench/indent_convergence_doc.py reads them): each ladder is a scene of input/ on a family of meshes indexed by
h_tip, and a result is one rung's outputs, kept in a JSON file under its key "model[@tol]:h_tip"."""
import json
import math

R2 = math.sqrt(2)
KEYS = ("load at end of loading", "depth at end of loading", "creep depth", "residual depth")
OUT3 = ("load at end of loading", "creep depth", "residual depth")  # the three outputs a mesh is judged on
SHORT = {"load at end of loading": "P", "depth at end of loading": "h_max", "creep depth": "creep",
         "residual depth": "h_res"}


def model(label, name, order, far, r_fine, hs, group, nested=None):
    """A ladder: its scene (input/NAME.yaml), element order, h_far / h_tip, r_fine (None: as shipped), h_tip's;
    nested: the h_tip of one mesh whose tetrahedra are split into eight once per halving of h_tip (so every rung's
    mesh holds the one before it), instead of a new mesh per rung."""
    return dict(label=label, scene=name, order=order, far=far, r_fine=r_fine, hs=hs, group=group, nested=nested)


K, B = "nanoindent_kerogen_sector", "microindent_BN_sector"
MODELS = {
    "sector2": model("60° sector, P2", K, 2, 4, 0.9, [0.2, 0.1414, 0.12, 0.1, 0.07071, 0.05, 0.03536], "kerogen"),
    "sector1": model("60° sector, P1", K, 1, 8, 0.9, [0.1, 0.07071, 0.05, 0.03536, 0.025, 0.01768], "kerogen"),
    "sector2f8": model("60° sector, P2, h_far 8 h_tip", K, 2, 8, 0.9, [0.1414, 0.12, 0.1, 0.07071], "kerogen"),
    "sector2n": model("60° sector, P2, nested (the h_tip 0.2 mesh split)", K, 2, 4, 0.9, [0.2, 0.1, 0.05], "kerogen", 0.2),
    "sector1n": model("60° sector, P1, nested (the h_tip 0.2 mesh split)", K, 1, 4, 0.9, [0.1, 0.05, 0.025], "kerogen",
                      0.2),
    "half2": model("half model (cube), P2", "nanoindent_kerogen", 2, 4, 0.9, [0.12], "kerogen"),
    "old1": model("60° sector, P1, r_fine 0.4 (the scenes before)", K, 1, 8, 0.4, [0.1, 0.07071, 0.05], "kerogen"),
    "axi1": model("axisymmetric cone, P1", "nanoindent_kerogen_axi", 1, 7.5, None,
                  [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01, 0.01 / R2, 0.005], "kerogen"),
    "axi2": model("axisymmetric cone, P2", "nanoindent_kerogen_axi", 2, 7.5, None,
                  [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01], "kerogen"),
    "bn2": model("BN, 60° sector, P2", B, 2, 8, None, [5, 3.536, 2.5, 1.768, 1.25, 0.8839], "BN"),
    "bn1": model("BN, 60° sector, P1", B, 1, 8, None, [2.5, 1.768, 1.25, 0.8839, 0.625], "BN"),
    "bnaxi2": model("BN, axisymmetric cone, P2", "microindent_BN_axi", 2, 7.5, None,
                    [0.5, 0.5 / R2, 0.25, 0.25 / R2, 0.125], "BN"),
    "bnaxi1": model("BN, axisymmetric cone, P1", "microindent_BN_axi", 1, 7.5, None,
                    [0.5, 0.5 / R2, 0.25, 0.25 / R2, 0.125, 0.125 / R2], "BN"),
    "bp2": model("BP, half model (cube), P2", "microindent_BP", 2, 8, None, [5, 3.536, 2.5, 1.768, 1.25], "BP"),
}


def load(path):
    return json.loads(path.read_text()) if path.exists() else {}


def key(model, h, tol=None):
    return f"{model}{'@' + format(tol, 'g') if tol else ''}:{h:.6g}"


def ladder(res, model, tol=None):
    """The finished rungs of a ladder, coarsest first."""
    return sorted((r for r in res.values() if r["model"] == model and r.get("tol") == tol and "failed" not in r),
                  key=lambda r: -r["h_tip"])


def ladders(res, group=None):
    """(model, tol) of every ladder in res (of one group), in MODELS' order, the shipped tolerance first."""
    found = {(r["model"], r.get("tol")) for r in res.values()
             if "failed" not in r and r["model"] in MODELS and group in (None, MODELS[r["model"]]["group"])}
    return sorted(found, key=lambda mt: (list(MODELS).index(mt[0]), mt[1] is not None, mt[1] or 0))
