"""Spacetimes and geodesics from Python: exact deflection angles, the command-line program's
answers, the physics of single trajectories, the bulk tracer against the single one, and errors
that name their parameter.

Needs mpmath (a test dependency) for the exact Schwarzschild deflection angle.
"""

import json
import subprocess

import mpmath
import numpy as np
import pytest

import nullpath

SCHWARZSCHILD = nullpath.Spacetime("schwarzschild", mass=1.0)
IMPACTS = [5.3, 5.5, 6.0, 8.0, 12.0, 30.0, 100.0]


def exact_deflection(b, mass=1.0):
    """Schwarzschild's bending angle of light with impact parameter b (Darwin 1959; Bozza 2002,
    eq. 4 in elliptic form): with the closest approach r0 (the largest root of
    r³ − b² r + 2M b² = 0), Q² = (r0 − 2M)(r0 + 6M), k² = (Q − r0 + 6M)/(2Q) and
    sin² φ0 = (Q − r0 + 2M)/(Q − r0 + 6M),
    α = 4 √(r0/Q) [K(k) − F(φ0, k)] − π."""
    mpmath.mp.dps = 40
    b, m = mpmath.mpf(b), mpmath.mpf(mass)
    r0 = 2 * b / mpmath.sqrt(3) * mpmath.cos(mpmath.acos(-3 * mpmath.sqrt(3) * m / b) / 3)
    q = mpmath.sqrt((r0 - 2 * m) * (r0 + 6 * m))
    k2 = (q - r0 + 6 * m) / (2 * q)
    phi0 = mpmath.asin(mpmath.sqrt((q - r0 + 2 * m) / (q - r0 + 6 * m)))
    alpha = 4 * mpmath.sqrt(r0 / q) * (mpmath.ellipk(k2) - mpmath.ellipf(phi0, k2)) - mpmath.pi
    return float(alpha)


def test_the_exact_formula_knows_its_limits():
    # Weak field: 4M/b + 15π M²/(4 b²) + 128 M³/(3 b³) + ….
    b = 1e4
    assert exact_deflection(b) == pytest.approx(4 / b + 15 * np.pi / (4 * b**2) + 128 / (3 * b**3), rel=1e-11)
    # Near the photon sphere (b → 3√3 M) the angle grows without bound.
    assert exact_deflection(5.1962) > 5.0


@pytest.mark.parametrize("b", IMPACTS)
def test_deflections_match_the_exact_angle(b):
    (angle,) = nullpath.deflections(SCHWARZSCHILD, [b])
    assert angle == pytest.approx(exact_deflection(b), abs=1e-7)


def test_deflections_match_the_command_line(nullpath_bin):
    angles = nullpath.deflections(SCHWARZSCHILD, IMPACTS)
    for b, angle in zip(IMPACTS, angles):
        line = [str(nullpath_bin), "geodesic", "--spacetime", "schwarzschild", "--impact", repr(b), "--json"]
        printed = json.loads(subprocess.run(line, check=True, capture_output=True, text=True).stdout)
        assert printed["fate"] == "escaped"
        assert angle == pytest.approx(printed["deflection_rad"], abs=1e-12)


def test_captured_rays_have_no_deflection():
    angles = nullpath.deflections(SCHWARZSCHILD, [0.0, 5.0, -5.0, 6.0])
    assert np.isnan(angles[:3]).all() and np.isfinite(angles[3])
    # A Kerr hole bends prograde rays less than retrograde ones.
    kerr = nullpath.Spacetime("kerr", spin=0.9)
    prograde, retrograde = nullpath.deflections(kerr, [8.0, -8.0])
    assert 0 < prograde < retrograde


def test_a_trajectory_is_null_and_keeps_its_constants():
    g = nullpath.geodesic(SCHWARZSCHILD, [10.0, 0.0, 0.0], [0.3, 1.0, 0.2])
    assert g["fate"] == "escaped" and g["failure"] is None
    n = len(g["lambda"])
    assert n > 10
    for key in ("t", "x", "y", "z", "hamiltonian", "E", "L_z"):
        assert g[key].shape == (n,)
    assert g["p"].shape == (n, 4)
    assert g["Q"] is None
    assert np.abs(g["hamiltonian"]).max() < 1e-9
    # E = −p_t and L_z = x p_y − y p_x, kept along the ray, as the arrays show them.
    assert np.array_equal(g["E"], -g["p"][:, 0])
    assert np.allclose(g["L_z"], g["x"] * g["p"][:, 2] - g["y"] * g["p"][:, 1], atol=1e-12)
    assert np.ptp(g["E"]) < 1e-9 * g["E"][0] and np.ptp(g["L_z"]) < 1e-9 * abs(g["L_z"][0])
    # Unit energy for the static observer at r = 10: E = √(1 − 2M/r).
    assert g["E"][0] == pytest.approx(np.sqrt(1 - 2 / 10), rel=1e-12)
    # Forwards in time, from the start, outwards.
    assert (np.diff(g["t"]) > 0).all() and (np.diff(g["lambda"]) > 0).all()
    assert [g["x"][0], g["y"][0], g["z"][0]] == [10.0, 0.0, 0.0]
    assert np.hypot(g["x"][-1], g["y"][-1]) > 900


def test_kerr_keeps_carters_constant():
    kerr = nullpath.Spacetime("kerr", mass=1.0, spin=0.9)
    g = nullpath.geodesic(kerr, [8.0, 0.0, 3.0], [-0.2, 1.0, 0.4])
    assert g["fate"] == "escaped"
    assert g["Q"] is not None and g["Q"][0] > 0
    assert np.ptp(g["Q"]) < 1e-8 * g["Q"][0]
    assert np.ptp(g["L_z"]) < 1e-8 * abs(g["L_z"][0]) and g["L_z"][0] > 0
    assert np.abs(g["hamiltonian"]).max() < 1e-9


def test_a_radial_ray_falls_in():
    g = nullpath.geodesic(SCHWARZSCHILD, [0.0, 0.0, 20.0], [0.0, 0.0, -1.0])
    assert g["fate"] == "captured" and np.isnan(g["direction"]).all()
    # It ends inside the horizon, the chart regular there.
    assert np.hypot(np.hypot(g["x"][-1], g["y"][-1]), g["z"][-1]) < 2.0
    assert np.isfinite(g["t"]).all()


@pytest.mark.parametrize("spacetime", [SCHWARZSCHILD, nullpath.Spacetime("kerr", spin=0.7)], ids=repr)
def test_an_escaping_ray_ends_as_the_bulk_tracer_says(spacetime):
    position, direction = [12.0, 1.0, -2.0], [-0.3, 0.9, 0.1]
    one = nullpath.geodesic(spacetime, position, direction)
    many = nullpath.geodesics(spacetime, position, [direction])
    assert nullpath.FATES[many["fate"][0]] == one["fate"] == "escaped"
    assert np.allclose(many["direction"][0], one["direction"], atol=1e-7)


def random_directions(n, seed=7):
    d = np.random.default_rng(seed).normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


@pytest.mark.parametrize(
    "spacetime",
    [SCHWARZSCHILD, nullpath.Spacetime("kerr", spin=0.9), nullpath.Spacetime("ellis", throat=1.0)],
    ids=repr,
)
def test_many_rays_end_as_each_ray_alone(spacetime):
    position = np.array([0.0, 1.0, 5.0])
    directions = random_directions(60)
    many = nullpath.geodesics(spacetime, position, directions)
    assert many["fate"].dtype == np.uint8 and many["direction"].shape == (60, 3)
    for i, d in enumerate(directions):
        one = nullpath.geodesic(spacetime, position, d)
        assert nullpath.FATES[many["fate"][i]] == one["fate"], i
        if one["fate"] in ("escaped", "traversed"):
            assert np.allclose(many["direction"][i], one["direction"], atol=1e-6), i
    fates = set(nullpath.FATES[f] for f in many["fate"])
    assert fates & {"captured", "traversed"} and "escaped" in fates


def test_many_rays_whatever_the_threads():
    directions = random_directions(2000, seed=3)
    positions = np.tile([0.0, 0.0, -30.0], (2000, 1))
    one = nullpath.geodesics(SCHWARZSCHILD, positions, directions, threads=1)
    four = nullpath.geodesics(SCHWARZSCHILD, positions, directions, threads=4)
    every = nullpath.geodesics(SCHWARZSCHILD, positions, directions)
    for key in ("fate", "steps"):
        assert np.array_equal(one[key], four[key]) and np.array_equal(one[key], every[key])
    assert np.array_equal(one["direction"], four["direction"], equal_nan=True)
    angles = nullpath.deflections(SCHWARZSCHILD, np.linspace(5.3, 50, 40), threads=1)
    assert np.array_equal(angles, nullpath.deflections(SCHWARZSCHILD, np.linspace(5.3, 50, 40), threads=3))


def test_spacetimes_lists_the_registry():
    listed = {s["name"]: s for s in nullpath.spacetimes()}
    assert {"minkowski", "schwarzschild", "kerr", "kerr-newman", "ellis", "wormhole"} <= set(listed)
    kerr = listed["kerr"]
    assert [p["name"] for p in kerr["parameters"]] == ["mass", "spin"]
    assert kerr["constraint"] == "|spin| ≤ mass"
    for s in listed.values():
        # The one parameter with no default, the wormhole's lensing width, is given.
        values = {p["name"]: 0.05 if p["default"] is None else p["default"] for p in s["parameters"]}
        built = nullpath.Spacetime(s["name"], **values)
        assert built.name == s["name"] and built.parameters == pytest.approx(values)


def raises_naming(parameter, build):
    with pytest.raises(nullpath.SpacetimeError) as caught:
        build()
    assert isinstance(caught.value, ValueError)
    assert caught.value.parameter == parameter
    if parameter is not None:
        assert parameter in str(caught.value)
    return str(caught.value)


def test_bad_parameters_raise_naming_the_parameter():
    message = raises_naming("spin", lambda: nullpath.Spacetime("kerr", mass=1.0, spin=1.5))
    assert message == "kerr spacetime: spin: |spin| must be ≤ mass = 1, got 1.5"
    raises_naming("mass", lambda: nullpath.Spacetime("schwarzschild", mass=-1.0))
    raises_naming("mass", lambda: nullpath.Spacetime("schwarzschild", mass="heavy"))
    raises_naming("charge", lambda: nullpath.Spacetime("kerr-newman", spin=0.8, charge=0.7))
    raises_naming("charge", lambda: nullpath.Spacetime("schwarzschild", charge=0.1))
    raises_naming(None, lambda: nullpath.Spacetime("kerrr"))
    raises_naming("spin", lambda: nullpath.Spacetime.from_dict({"type": "kerr", "mass": 1.0, "spin": 2.0}))
    raises_naming("mass", lambda: nullpath.Spacetime.from_toml('[spacetime]\ntype = "kerr"\nspin = 0.5\n'))
    raises_naming("rtol", lambda: nullpath.geodesic(SCHWARZSCHILD, [10, 0, 0], [0, 1, 0], rtol=2.0))
    raises_naming("direction", lambda: nullpath.geodesic(SCHWARZSCHILD, [10, 0, 0], [0, 0, 0]))
    raises_naming("position", lambda: nullpath.geodesic(SCHWARZSCHILD, [10, 0], [0, 1, 0]))
    raises_naming("escape_radius", lambda: nullpath.geodesic(SCHWARZSCHILD, [10, 0, 0], [0, 1, 0], escape_radius=5))
    raises_naming("observer", lambda: nullpath.geodesic(SCHWARZSCHILD, [10, 0, 0], [0, 1, 0], observer="falling"))
    raises_naming("threads", lambda: nullpath.geodesics(SCHWARZSCHILD, [10, 0, 0], [0, 1, 0], threads=0))
    raises_naming("inclination", lambda: nullpath.deflections(SCHWARZSCHILD, [6.0], inclination=200))
    raises_naming("directions", lambda: nullpath.geodesics(SCHWARZSCHILD, np.zeros((2, 3)) + 10, np.ones((3, 3))))
    raises_naming("positions", lambda: nullpath.geodesics(nullpath.Spacetime("ellis"), [0.5, 0, 0], [0, 1, 0]))


WRITTEN_SCHWARZSCHILD = {
    "type": "metric",
    "coordinates": "spherical",
    "parameters": {"M": 1.0},
    "g_tt": "-(1 - 2*M/r)",
    "g_rr": "1/(1 - 2*M/r)",
    "g_thetatheta": "r^2",
    "g_phiphi": "r^2*sin(theta)^2",
}


def test_a_written_metric_bends_light_as_the_built_in_one():
    written = nullpath.Spacetime.from_dict(WRITTEN_SCHWARZSCHILD)
    assert written.name == "metric" and written.parameters == {}
    impacts = [6.0, 10.0, 30.0]
    # The written metric is traced in 4-D with derivatives by automatic differentiation, the
    # built-in one in the ray's plane: two integrations of one exact bending.
    assert np.allclose(nullpath.deflections(written, impacts), nullpath.deflections(SCHWARZSCHILD, impacts), rtol=1e-7, atol=0)
    # From TOML text too, with the scene reader's checks.
    text = "[spacetime]\n" + "\n".join(f"{k} = {json.dumps(v)}" for k, v in WRITTEN_SCHWARZSCHILD.items() if k != "parameters")
    text += "\nparameters = { M = 1.0 }\n"
    assert nullpath.Spacetime.from_toml(text) == written
    # Nothing shows a written metric time-symmetric: its light is not followed forwards.
    raises_naming("spacetime", lambda: nullpath.geodesic(written, [10, 0, 0], [0, 1, 0]))
