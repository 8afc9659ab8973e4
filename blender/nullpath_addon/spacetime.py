"""The spacetime a hole Empty stands for, as nullpath's `[spacetime]` table (docs/scene-format.md).

Plain Python (no `bpy`), so the rules live in one place: which metric a black hole's parameters
pick, the size of its horizon or throat, and the checks nullpath would make, worded for Blender.
"""

import math

BLACK_HOLE = "BLACK_HOLE"
WORMHOLE = "WORMHOLE"
# Wormhole shapes: Ellis's (a throat only) and the Interstellar one of James et al. (2015).
ELLIS = "ELLIS"
INTERSTELLAR = "INTERSTELLAR"


def black_hole_type(spin, charge):
    """The metric of a hole with these parameters: the simplest one that has them all."""
    if spin == 0.0:
        return "schwarzschild" if charge == 0.0 else "reissner-nordstrom"
    return "kerr" if charge == 0.0 else "kerr-newman"


def horizon_radius(mass, spin, charge):
    """Outer horizon radius r₊ = M + √(M² − a² − Q²) (Boyer–Lindquist), for a hole that has one."""
    return mass + math.sqrt(max(mass * mass - spin * spin - charge * charge, 0.0))


def check_black_hole(name, mass, spin, charge):
    """None, or why nullpath would refuse this hole (the same bounds as its scene reader)."""
    if mass < 0.0:
        return f"{name}: mass must be ≥ 0, got {mass:g}"
    if spin * spin + charge * charge > mass * mass:
        return (
            f"{name}: spin² + charge² must be ≤ mass² (a naked singularity otherwise), "
            f"got spin {spin:g}, charge {charge:g}, mass {mass:g}"
        )
    return None


def check_wormhole(name, shape, throat, length, lensing_width):
    """None, or why nullpath would refuse this wormhole."""
    if throat <= 0.0:
        return f"{name}: throat must be > 0, got {throat:g}"
    if shape == INTERSTELLAR:
        if length < 0.0:
            return f"{name}: length must be ≥ 0, got {length:g}"
        if lensing_width < 1e-9 * throat:
            return f"{name}: lensing width must be ≥ 10⁻⁹ × throat, got {lensing_width:g}"
    return None


def black_hole_table(mass, spin, charge, axis):
    """`[spacetime]` of a black hole; `axis` (a unit vector, nullpath's y-up world) only for a
    spinning one, the only kind whose metric takes it."""
    table = {"type": black_hole_type(spin, charge), "mass": mass}
    if spin != 0.0:
        table["spin"] = spin
    if charge != 0.0:
        table["charge"] = charge
    if spin != 0.0:
        table["axis"] = list(axis)
    return table


def wormhole_table(shape, throat, length, lensing_width):
    """`[spacetime]` of a wormhole."""
    if shape == ELLIS:
        return {"type": "ellis", "throat": throat}
    return {"type": "wormhole", "throat": throat, "length": length, "lensing_width": lensing_width}
