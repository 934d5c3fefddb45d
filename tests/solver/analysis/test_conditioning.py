"""Accuracy next to singular poses, against a 50-digit reference (mpmath).

Four-bars, slider-cranks and inverted slider-cranks drawn at random poses 1e-3 ... 1e-10 rad from
a dead centre (a limit position: the dyad is flat, its two branches about to meet) or from the
flat pose of a change-point linkage. The pose is the drawn coordinates (floats, taken as exact);
the reference solves the velocity and acceleration equations there in 50 digits, each derived
independently of the solver (complex loop closure for the four-bar, the slider's two components
for the slider-crank, transport plus relative motion of the block for the inverted one).

The contract: every pose whose condition number is below 1e12 is answered (no
singular_configuration); the rates are right to 1e-9 (relative to the largest rate of their kind)
where cond < 1e6 and to cond x 1e-15 above, the rounding of a solve at the given coordinates; the
reported condition number agrees with the one at the exact pose (the same definition, evaluated
in 50 digits) to a factor of 10; a pose exactly at a dead centre is refused.
"""

from __future__ import annotations

from typing import Any

import mpmath as mp
import numpy as np
import pytest

from solver.analysis.instant import MAX_CONDITION_NUMBER, LinkageAnalysis, analyze
from solver.errors import SingularConfiguration
from solver.model.scene import parse_linkage
from solver.teaching.presets import build_preset

mp.mp.dps = 50
DISTANCES = ("1e-3", "1e-4", "1e-6", "1e-8", "1e-10")
OMEGA, ALPHA = -2.0, 3.0
Doc = dict[str, Any]


def _z(doc: Doc, name: str) -> Any:
    x, y = doc["points"][name]
    return mp.mpc(x, y)


def _cross(u: Any, w: Any) -> Any:
    return u.real * w.imag - u.imag * w.real


def _solve(rows: list[list[Any]], rhs: list[Any]) -> list[Any]:
    return list(mp.lu_solve(mp.matrix(rows), mp.matrix(rhs)))


def bound(cond: float) -> float:
    return 1e-9 if cond < 1e6 else cond * 1e-15


# --- the references ------------------------------------------------------------------------------


def four_bar_rates(doc: Doc) -> dict[str, Any]:
    """Loop closure B - A + C - B = D - A + C - D differentiated (k x r = i r):
    omega2 (C - B) - omega3 (C - D) = -omega1 (B - A); alpha likewise with the omega^2 terms."""
    A, B, C, D = (_z(doc, p) for p in "ABCD")
    cb, cd, ba = C - B, C - D, B - A
    rows = [[cb.real, -cd.real], [cb.imag, -cd.imag]]
    w2, w3 = _solve(rows, [-OMEGA * ba.real, -OMEGA * ba.imag])
    a_B = (1j * ALPHA - OMEGA**2) * ba
    rhs = -1j * (-a_B + w2**2 * cb - w3**2 * cd)
    a2, a3 = _solve(rows, [rhs.real, rhs.imag])
    return {"omega": {"coupler": w2, "rocker": w3}, "alpha": {"coupler": a2, "rocker": a3}}


def slider_rates(doc: Doc) -> dict[str, Any]:
    """C slides along x: v_C = (vx, 0) with (C - B).(v_C - v_B) = 0, a_C = (ax, 0) with
    (C - B).(a_C - a_B) + |v_C - v_B|^2 = 0; the rod's omega and alpha from r x v_rel / |r|^2."""
    A, B, C = (_z(doc, p) for p in "ABC")
    r, ba = C - B, B - A
    v_B, a_B = 1j * OMEGA * ba, (1j * ALPHA - OMEGA**2) * ba
    vx = (r.real * v_B.real + r.imag * v_B.imag) / r.real
    v_rel = vx - v_B
    ax = (r.real * a_B.real + r.imag * a_B.imag - abs(v_rel) ** 2) / r.real
    a_rel = ax - a_B
    length2 = abs(r) ** 2
    return {
        "omega": {"coupler": _cross(r, v_rel) / length2},
        "alpha": {"coupler": _cross(r, a_rel) / length2},
    }


def inverted_rates(doc: Doc) -> dict[str, Any]:
    """The block at A in the lever's slot (direction u, pivot C): v_A = omega_l k x r + s' u and
    a_A = alpha_l k x r - omega_l^2 r + 2 omega_l s' k x u + s'' u, each a 2x2 system."""
    pivot, A, C = (_z(doc, p) for p in "OAC")
    axis = next(j["axis"] for j in doc["joints"] if j["type"] == "slider")
    u = mp.mpc(*axis) / abs(mp.mpc(*axis))
    r, oa = A - C, A - pivot
    v_A, a_A = 1j * OMEGA * oa, (1j * ALPHA - OMEGA**2) * oa
    rows = [[(1j * r).real, u.real], [(1j * r).imag, u.imag]]
    w, s_dot = _solve(rows, [v_A.real, v_A.imag])
    rest = a_A + w**2 * r - 2 * w * s_dot * 1j * u
    a, _ = _solve(rows, [rest.real, rest.imag])
    return {"omega": {"lever": w}, "alpha": {"lever": a}}


# --- the families: drawn next to a singular pose --------------------------------------------------


def _limit_angle(g: Any, a: Any, reach: Any) -> Any:
    """The crank angle where |B - D| = reach (B = a e^(i t), D = (g, 0))."""
    return 2 * mp.asin(mp.sqrt((reach - abs(g - a)) * (reach + abs(g - a)) / (4 * a * g)))


def four_bar_near_dead_centre(distance: Any, side: int) -> Doc:
    """S000-T1-like triple rocker (g 2.5, a 1, b 2, c sqrt(1.25)) drawn ``distance`` rad inside its
    limit |BD| = b + c (side +1 upper limit, -1 lower)."""
    g, a, b, c = mp.mpf("2.5"), mp.mpf(1), mp.mpf(2), mp.sqrt(mp.mpf("1.25"))
    angle = side * (_limit_angle(g, a, b + c) - distance)
    return _four_bar(g, a, b, c, angle)


def four_bar_near_change_point(distance: Any, side: int) -> Doc:
    """A change-point four-bar (g 1, a 0.4, b 0.9, c 0.5: a + g = b + c) drawn ``distance`` rad
    from its flat pose at crank 180 deg, C on the open side."""
    g, a, b, c = mp.mpf(1), mp.mpf("0.4"), mp.mpf("0.9"), mp.mpf("0.5")
    return _four_bar(g, a, b, c, mp.pi + side * distance)


def _four_bar(g: Any, a: Any, b: Any, c: Any, angle: Any) -> Doc:
    A, D = mp.mpc(0), mp.mpc(g)
    B = a * mp.expj(angle)
    d = abs(D - B)
    along = (d * d + b * b - c * c) / (2 * d)
    h = mp.sqrt(max(b * b - along * along, 0))
    C = B + mp.mpc(along, h) * (D - B) / d
    doc = build_preset("four_bar", {"omega": OMEGA, "alpha": ALPHA})
    doc["points"] = {
        name: [float(z.real), float(z.imag)] for name, z in zip("ABCD", (A, B, C, D), strict=True)
    }
    doc["links"]["coupler"]["points"] = ["B", "C"]
    return doc


def slider_near_dead_centre(distance: Any, side: int) -> Doc:
    """Offset slider-crank (crank 1, offset 0.2, rod 1.1 < 1.2: it rocks) drawn ``distance`` rad
    inside the limit where the rod stands perpendicular to the guide (B_y = e - rod)."""
    a, e, rod = mp.mpf(1), mp.mpf("0.2"), mp.mpf("1.1")
    limit = mp.asin((e - rod) / a)  # -64.2 deg, and -pi - limit on the other side
    angle = limit + distance if side > 0 else -mp.pi - limit - distance
    return _slider(a, e, rod, angle)


def slider_near_change_point(distance: Any, side: int) -> Doc:
    """In-line slider-crank with rod = crank (a change point at crank 90 deg, where C = A), drawn
    ``distance`` rad from it."""
    return _slider(mp.mpf(1), mp.mpf(0), mp.mpf(1), mp.pi / 2 + side * distance)


def _slider(a: Any, e: Any, rod: Any, angle: Any) -> Doc:
    B = a * mp.expj(angle)
    x = B.real + mp.sqrt(rod * rod - (e - B.imag) ** 2)
    doc = build_preset("slider_crank", {"offset": 0.0, "omega": OMEGA, "alpha": ALPHA})
    doc["points"] = {
        "A": [0.0, 0.0],
        "B": [float(B.real), float(B.imag)],
        "C": [float(x), float(e)],
    }
    doc["links"]["coupler"]["points"] = ["B", "C"]
    return doc


def inverted_near_dead_centre(distance: Any, side: int) -> Doc:
    """Inverted slider-crank (ground 1, crank 0.85, slot offset 0.2 > g - a: it rocks) drawn
    ``distance`` rad outside the window where |CA| < e (the slot cannot reach the pin)."""
    g, a, e = mp.mpf(1), mp.mpf("0.85"), mp.mpf("0.2")
    angle = side * (_limit_angle(g, a, e) + distance)
    pivot, C = mp.mpc(0), mp.mpc(g)
    A = a * mp.expj(angle)
    r = A - C
    along = mp.sqrt(abs(r) ** 2 - e * e)
    u = r / abs(r) * mp.expj(-mp.asin(e / abs(r)))
    D = C + (along + 1j * e) * u
    doc = build_preset("inverted_slider_crank", {"omega": OMEGA, "alpha": ALPHA})
    doc["points"] = {
        name: [float(z.real), float(z.imag)]
        for name, z in zip("OACD", (pivot, A, C, D), strict=True)
    }
    slider = next(j for j in doc["joints"] if j["type"] == "slider")
    slider["axis"] = [float(u.real), float(u.imag)]
    return doc


FAMILIES = {
    "four_bar_dead_centre": (four_bar_near_dead_centre, four_bar_rates),
    "four_bar_change_point": (four_bar_near_change_point, four_bar_rates),
    "slider_dead_centre": (slider_near_dead_centre, slider_rates),
    "slider_change_point": (slider_near_change_point, slider_rates),
    "inverted_dead_centre": (inverted_near_dead_centre, inverted_rates),
}


def errors(result: LinkageAnalysis, rates: dict[str, Any]) -> float:
    """The largest rate error relative to the largest rate of its kind (alpha: + omega^2)."""
    worst = 0.0
    for kind in ("omega", "alpha"):
        scale = max(abs(float(v)) for v in rates[kind].values())
        if kind == "alpha":
            scale += max(abs(float(v)) for v in rates["omega"].values()) ** 2
        for link, value in rates[kind].items():
            got = getattr(result.links[link], kind)
            worst = max(worst, abs(got - float(value)) / scale)
    return worst


def exact_condition(doc: Doc) -> float:
    """The solver's condition number (velocity system, rotation columns scaled by the size) of
    the same pose, its Jacobian's singular values computed in 50 digits."""
    from solver.position.assembly import DriverInput, assemble
    from solver.position.constraints import ConstraintSystem, KnownPoses
    from solver.position.topology import build_plan

    scene = parse_linkage(doc)
    plan = build_plan(scene)
    at_rest = [DriverInput(np.zeros(1), np.zeros(1), np.zeros(1)) for _ in scene.drivers]
    motion = assemble(scene, plan, at_rest, 0)  # the drawn pose: every driver turned by 0
    system = ConstraintSystem(scene, scene.moving_links, drivers=True)
    _, J, _ = system.equations(KnownPoses(motion.links, scene).at(0), 0)
    J = J.copy()
    J[:, 2::3] /= scene.size
    J[-len(scene.drivers) :] *= scene.size
    values = mp.svd_r(mp.matrix(J.tolist()), compute_uv=False)
    return float(max(values) / min(values))


@pytest.mark.parametrize("distance", DISTANCES)
@pytest.mark.parametrize("side", [1, -1], ids=["plus", "minus"])
@pytest.mark.parametrize("family", list(FAMILIES))
def test_answered_to_the_digits_the_conditioning_allows(
    family: str, side: int, distance: str
) -> None:
    make, reference = FAMILIES[family]
    doc = make(mp.mpf(distance), side)
    result = analyze(parse_linkage(doc), ["velocity", "acceleration"])
    cond = result.diagnostics.condition_number
    assert cond is not None and cond < MAX_CONDITION_NUMBER
    exact = exact_condition(doc)
    assert exact / 10.0 <= cond <= 10.0 * exact, (cond, exact)
    error = errors(result, reference(doc))
    assert error <= bound(cond), (error, cond)


@pytest.mark.parametrize("family", ["four_bar_dead_centre", "slider_dead_centre"])
def test_exactly_at_a_dead_centre_is_refused(family: str) -> None:
    """Drawn exactly at the limit (the coordinates collinear to the last bit): refused."""
    make, _ = FAMILIES[family]
    doc = make(mp.mpf(0), 1)
    with pytest.raises(SingularConfiguration):
        analyze(parse_linkage(doc), ["velocity"])


@pytest.mark.parametrize("distance", ["1e-4", "1e-5", "1e-6"])
def test_posed_next_to_a_change_point_is_answered(distance: str) -> None:
    """The change-point four-bar drawn far from its flat pose and posed with angle_deg 1e-4 ...
    1e-6 rad from it: the dyad is flat to h ~ distance x size, far above rounding, so the pose is
    answered (not singular_configuration), its condition number within a factor 10 of the
    exact pose's, the rates within 10 cond^2 eps of the 50-digit ones (a posed angle is a float:
    its rounding moves the pose by cond eps, which the rates amplify by cond again)."""
    exact_doc = four_bar_near_change_point(mp.mpf(distance), 1)
    doc = four_bar_near_change_point(mp.mpf(1), 1)
    doc["drivers"][0]["angle_deg"] = float(mp.degrees(mp.pi + mp.mpf(distance)))
    result = analyze(parse_linkage(doc), ["velocity", "acceleration"])
    cond = result.diagnostics.condition_number
    assert cond is not None
    exact = exact_condition(exact_doc)
    assert exact / 10.0 <= cond <= 10.0 * exact, (cond, exact)
    rates = four_bar_rates(exact_doc)
    scale = max(abs(float(v)) for v in rates["omega"].values())
    for link, value in rates["omega"].items():
        got = result.links[link].omega
        assert abs(got - float(value)) <= 10.0 * cond**2 * 2.2e-16 * scale, (link, got, value)
