"""Richardson extrapolation of a ladder of meshes (camclay9.indent3d_study, camclay9.indent2d_study)."""
import math


def richardson(hs, xs):
    """The last three rungs (constant ratio): observed order and limit; None where not monotone or contracting."""
    if len(xs) < 3:
        return None, None
    (h1, h2, _), (x1, x2, x3) = hs[-3:], xs[-3:]
    r = h1 / h2
    d1, d2 = x1 - x2, x2 - x3
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(d1 / d2) / math.log(r)
    if not 0.5 <= p <= 4:  # erratic: the rungs' differences are the time step's or the contact's noise
        return p, None
    return p, x3 + (x3 - x2) / (r ** p - 1)
