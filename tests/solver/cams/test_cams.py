"""Cams (issue 24): the laws against the textbooks' peak factors derived independently (sympy
from each law's definition; Norton, Design of Machinery, table 8-3), the rates by finite
differences, the profile by the contact condition at every sample, the pressure angle and the
radius of curvature against Norton's explicit formulas and finite differences of the profile,
and the warnings."""

from __future__ import annotations

import copy
import math
from typing import Any

import numpy as np
import pytest
import sympy as sp

import solver
from solver.cams import LAW_NAMES, LAWS, cam_geometry, follower_lift, parse_cam

OMEGA = 10.0
H = 0.025
BETA_DEG = 120.0


def scene(
    rise: str = "cycloidal",
    ret: str = "polynomial_345",
    follower: dict[str, Any] | None = None,
    base_radius: float = 0.04,
    omega: float = OMEGA,
    lift: float = H,
) -> dict[str, Any]:
    """The contract's example (docs/CAMS.md), with its laws, follower and sizes to vary."""
    return {
        "kind": "cam",
        "cam": {"base_radius": base_radius, "omega": omega},
        "follower": follower
        or {"motion": "translating", "contact": "roller", "roller_radius": 0.01, "offset": 0.005},
        "segments": [
            {"type": "rise", "law": rise, "lift": lift, "duration_deg": BETA_DEG},
            {"type": "dwell", "duration_deg": 60},
            {"type": "return", "law": ret, "lift": lift, "duration_deg": BETA_DEG},
            {"type": "dwell", "duration_deg": 60},
        ],
    }


ROLLER = {"motion": "translating", "contact": "roller", "roller_radius": 0.01, "offset": 0.005}
KNIFE = {"motion": "translating", "contact": "knife", "offset": -0.008}
FLAT = {"motion": "translating", "contact": "flat"}
OSCILLATING = {
    "motion": "oscillating",
    "contact": "roller",
    "roller_radius": 0.01,
    "pivot": [0.08, 0.02],
    "arm_length": 0.07,
}
OSCILLATING_FLAT = {"motion": "oscillating", "contact": "flat", "pivot": [0.08, 0.02]}
ANGULAR_LIFT = 0.3  # rad
FOLLOWERS = {
    "roller": (ROLLER, H),
    "knife": (KNIFE, H),
    "flat": (FLAT, H),
    "oscillating_roller": (OSCILLATING, ANGULAR_LIFT),
    "oscillating_flat": (OSCILLATING_FLAT, ANGULAR_LIFT),
}


# --- the laws: peak factors derived independently ------------------------------------------------

X = sp.symbols("x", real=True)


def _polynomial_law(name: str) -> sp.Expr:
    """The displacement laws as the textbooks define them."""
    return {
        "harmonic": (1 - sp.cos(sp.pi * X)) / 2,
        "cycloidal": X - sp.sin(2 * sp.pi * X) / (2 * sp.pi),
        "polynomial_345": 10 * X**3 - 15 * X**4 + 6 * X**5,
        "polynomial_4567": 35 * X**4 - 84 * X**5 + 70 * X**6 - 20 * X**7,
    }[name]


def _peak(expr: sp.Expr) -> float:
    """max |expr| on [0, 1]: at the ends or where its derivative vanishes (sympy's roots)."""
    candidates = [sp.Integer(0), sp.Integer(1)]
    for root in sp.solveset(sp.diff(expr, X), X, sp.Interval(0, 1)):
        candidates.append(root)
    return max(abs(float(expr.subs(X, c))) for c in candidates)


def _piecewise_acceleration(name: str) -> tuple[float, float]:
    """(C_v, C_a) of Norton's modified trapezoid and modified sine from their acceleration
    pieces, integrated by sympy with the amplitude A solved from y(1) = 1."""
    a_sym = sp.symbols("A", positive=True)
    pi = sp.pi
    eighth = sp.Rational(1, 8)
    if name == "modified_trapezoid":
        pieces = [
            (0, eighth, a_sym * sp.sin(4 * pi * X)),
            (eighth, 3 * eighth, a_sym),
            (3 * eighth, 5 * eighth, a_sym * sp.cos(4 * pi * (X - 3 * eighth))),
            (5 * eighth, 7 * eighth, -a_sym),
            (7 * eighth, 1, -a_sym * sp.cos(4 * pi * (X - 7 * eighth))),
        ]
    else:
        pieces = [
            (0, eighth, a_sym * sp.sin(4 * pi * X)),
            (eighth, 7 * eighth, a_sym * sp.cos(sp.Rational(4, 3) * pi * (X - eighth))),
            (7 * eighth, 1, -a_sym * sp.cos(4 * pi * (X - 7 * eighth))),
        ]
    v, y = sp.Integer(0), sp.Integer(0)
    v_half = None
    for x0, x1, acc in pieces:
        v_piece = v + sp.integrate(acc, (X, x0, X))
        if x0 <= sp.Rational(1, 2) <= x1:
            v_half = v_piece.subs(X, sp.Rational(1, 2))
        y = y + sp.integrate(v_piece, (X, x0, x1))
        v = v_piece.subs(X, x1)
    amplitude = sp.solve(sp.Eq(y, 1), a_sym)[0]
    assert v_half is not None
    return float(v_half.subs(a_sym, amplitude)), float(amplitude)


# Norton, Design of Machinery (5th ed.), table 8-3: the printed peak factors (C_v, C_a).
NORTON_TABLE = {
    "harmonic": (1.5708, 4.9348),
    "cycloidal": (2.0000, 6.2832),
    "polynomial_345": (1.8750, 5.7735),
    "polynomial_4567": (2.1875, 7.5132),
    "modified_trapezoid": (2.0000, 4.8881),
    "modified_sine": (1.7596, 5.5280),
}


@pytest.mark.parametrize("name", sorted(NORTON_TABLE))
def test_peak_factors_against_independent_derivation_and_norton(name: str) -> None:
    """Each law's C_v = max y' and C_a = max |y''| (the implementation, on 200001 points)
    equal sympy's from the law's definition to 1e-9, and Norton's table to its 5 digits."""
    if name in ("modified_trapezoid", "modified_sine"):
        c_v, c_a = _piecewise_acceleration(name)
    else:
        y = _polynomial_law(name)
        c_v, c_a = _peak(sp.diff(y, X)), _peak(sp.diff(y, X, 2))
    motion = LAWS[name](np.linspace(0.0, 1.0, 200001))
    assert motion.dy.max() == pytest.approx(c_v, rel=1e-9)
    assert np.abs(motion.d2y).max() == pytest.approx(c_a, rel=1e-9)
    table_v, table_a = NORTON_TABLE[name]
    assert c_v == pytest.approx(table_v, abs=6e-5)
    assert c_a == pytest.approx(table_a, abs=6e-5)


def test_textbook_peaks_in_si_units() -> None:
    """Cycloidal: v_max = 2 h omega / beta, a_max = 2 pi h omega^2 / beta^2; 3-4-5: 1.875 and
    5.7735 (10 / sqrt 3) times h omega / beta and h omega^2 / beta^2; harmonic: pi/2, pi^2/2."""
    beta = math.radians(BETA_DEG)
    cases = {
        "cycloidal": (2.0, 2.0 * math.pi),
        "polynomial_345": (1.875, 10.0 / math.sqrt(3.0)),
        "harmonic": (math.pi / 2.0, math.pi**2 / 2.0),
    }
    for law, (c_v, c_a) in cases.items():
        extremes = solver.sweep(scene(law, law), 360)["diagnostics"]["extremes"]
        assert extremes["velocity"]["max"] == pytest.approx(c_v * H * OMEGA / beta, rel=1e-6)
        peak_a = max(extremes["acceleration"]["max"], -extremes["acceleration"]["min"])
        assert peak_a == pytest.approx(c_a * H * OMEGA**2 / beta**2, rel=1e-5)


@pytest.mark.parametrize("name", LAW_NAMES)
def test_laws_start_at_zero_and_end_at_one(name: str) -> None:
    ends = LAWS[name](np.array([0.0, 1.0]))
    assert ends.y.tolist() == pytest.approx([0.0, 1.0], abs=1e-14)


# --- rates: finite differences -------------------------------------------------------------------


@pytest.mark.parametrize("name", LAW_NAMES)
@pytest.mark.parametrize("omega", [OMEGA, -3.0])
def test_rates_are_the_time_derivatives(name: str, omega: float) -> None:
    """v = ds/dt, a = dv/dt, j = da/dt by central differences in time (t = theta / |omega|)
    inside each segment, to 1e-6 of each quantity's largest magnitude."""
    doc = scene(name, name, omega=omega)
    cam = parse_cam(doc)
    step = 1e-5  # rad of cam angle
    theta = np.linspace(0.01, 2.0 * math.pi - 0.01, 2001)
    starts = np.array([s.start for s in cam.segments] + [2.0 * math.pi])
    inside = np.min(np.abs(theta[:, None] - starts[None, :]), axis=1) > 2 * step
    theta = theta[inside]
    w = abs(omega)
    dt = step / w

    def rates(t: np.ndarray) -> list[np.ndarray]:
        lift = follower_lift(cam, t)
        return [lift.s, lift.ds * w, lift.d2s * w**2, lift.d3s * w**3]

    ahead, here, behind = rates(theta + step), rates(theta), rates(theta - step)
    for k in range(3):
        difference = (ahead[k] - behind[k]) / (2.0 * dt)
        scale = max(np.abs(here[k + 1]).max(), 1e-12)
        assert np.abs(difference - here[k + 1]).max() <= 1e-6 * scale, (name, k)


# --- the profile ---------------------------------------------------------------------------------


def _profile_derivative(profile: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """d profile / d theta by central differences around the closed curve."""
    step = theta[1] - theta[0]
    return (np.roll(profile, -1, 0) - np.roll(profile, 1, 0)) / (2.0 * step)


def _to_ground(points: np.ndarray, theta: np.ndarray, omega: float) -> np.ndarray:
    """Cam-frame points seen in the ground when the cam has turned theta in its direction."""
    angle = math.copysign(1.0, omega) * theta
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]], 1)


def _pitch_points(doc: dict[str, Any], lift: np.ndarray) -> np.ndarray:
    """The roller centre (knife tip) in the ground from the scene's geometry, independently:
    translating on x = e at y = sqrt(R_p^2 - e^2) + s; oscillating at the arm's end, the arm
    at angle beta_0 + s from the pivot's line to the cam centre (counter-clockwise for a
    counter-clockwise cam)."""
    f = doc["follower"]
    rp = doc["cam"]["base_radius"] + f.get("roller_radius", 0.0)
    sign = math.copysign(1.0, doc["cam"]["omega"])
    if f["motion"] == "translating":
        e = f.get("offset", 0.0)
        return np.stack([np.full_like(lift, e), math.sqrt(rp**2 - e**2) + lift], 1)
    px, py = f["pivot"]
    d, arm = math.hypot(px, py), f["arm_length"]
    beta0 = math.acos((d**2 + arm**2 - rp**2) / (2 * d * arm))
    to_centre = math.atan2(-py, -sign * px)
    psi = to_centre + beta0 + lift
    return np.stack([sign * (sign * px + arm * np.cos(psi)), py + arm * np.sin(psi)], 1)


@pytest.mark.parametrize("name", sorted(FOLLOWERS))
@pytest.mark.parametrize("omega", [OMEGA, -OMEGA])
def test_profile_satisfies_the_contact_condition_at_every_sample(name: str, omega: float) -> None:
    """Turned to the ground at its angle, each profile point is the contact point, touches the
    follower (on the roller's circle, at the knife's tip, on the face's line) and the cam
    surface is tangent to the follower there; to 1e-6 m and 1e-4 rad on 20000 samples."""
    follower, lift = FOLLOWERS[name]
    doc = scene(follower=follower, omega=omega, lift=lift)
    body = solver.sweep(doc, 20000)
    theta = np.asarray(body["cam_angle"])
    profile = np.asarray(body["profile"])
    contact = _to_ground(profile, theta, omega)
    assert np.abs(contact - np.asarray(body["contact_point"])).max() < 1e-12
    tangent = _to_ground(_profile_derivative(profile, theta), theta, omega)
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    s = np.asarray(body["follower"]["displacement"])
    f = doc["follower"]
    if f["contact"] == "flat":
        if f["motion"] == "translating":
            face_normal = np.tile([0.0, 1.0], (s.size, 1))
            on_face = contact[:, 1] - (doc["cam"]["base_radius"] + s)
        else:
            pivot = np.array(f["pivot"], dtype=float)
            along = contact - pivot
            along /= np.linalg.norm(along, axis=1)[:, None]
            face_normal = np.stack([-along[:, 1], along[:, 0]], 1)
            # the face's distance from the cam centre, |pivot x along|
            distance = np.abs(pivot[0] * along[:, 1] - pivot[1] * along[:, 0])
            on_face = distance - distance  # the contact lies on the line through the pivot
            assert np.abs(distance - np.abs(_face_distance(doc, s))).max() < 1e-9
        assert np.abs(on_face).max() < 1e-9
        assert np.abs(np.einsum("ij,ij->i", tangent, face_normal)).max() < 1e-4
        return
    centre = _pitch_points(doc, s)
    radial = contact - centre
    r = f.get("roller_radius", 0.0)
    assert np.abs(np.linalg.norm(radial, axis=1) - r).max() < 1e-9
    if r > 0:
        radial /= r
        assert np.abs(np.einsum("ij,ij->i", tangent, radial)).max() < 1e-4


def _face_distance(doc: dict[str, Any], s: np.ndarray) -> np.ndarray:
    """An oscillating flat face through the pivot: its distance from the cam centre is
    d sin(beta_0 + s) with sin beta_0 = R_b / d."""
    d = math.hypot(*doc["follower"]["pivot"])
    beta0 = math.asin(doc["cam"]["base_radius"] / d)
    distance: np.ndarray = d * np.sin(beta0 + s)
    return distance


def test_the_roller_never_cuts_into_the_cam() -> None:
    """The envelope: every profile point lies on or outside every roller position (1e-9 m)."""
    doc = scene()
    body = solver.sweep(doc, 720)
    theta = np.asarray(body["cam_angle"])
    centres_in_cam = _to_ground(_pitch_points(doc, np.asarray(body["follower"]["displacement"])),
                                -theta, OMEGA)  # fmt: skip
    profile = np.asarray(body["profile"])
    gaps = np.linalg.norm(profile[:, None, :] - centres_in_cam[None, :, :], axis=2) - 0.01
    assert gaps.min() > -1e-9


# --- pressure angle and radius of curvature ------------------------------------------------------


@pytest.mark.parametrize("name", ["roller", "knife", "oscillating_roller"])
def test_pressure_angle_against_the_profiles_normal(name: str) -> None:
    """|phi| is the angle between the profile's normal (finite differences) at the contact and
    the follower's direction of motion there (along y, or square to the arm), to 1e-5 rad."""
    follower, lift = FOLLOWERS[name]
    doc = scene(follower=follower, lift=lift)
    body = solver.sweep(doc, 20000)
    theta = np.asarray(body["cam_angle"])
    tangent = _to_ground(_profile_derivative(np.asarray(body["profile"]), theta), theta, OMEGA)
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    s = np.asarray(body["follower"]["displacement"])
    if doc["follower"]["motion"] == "translating":
        direction = np.tile([0.0, 1.0], (s.size, 1))
    else:
        arm = _pitch_points(doc, s) - np.array(doc["follower"]["pivot"])
        direction = np.stack([-arm[:, 1], arm[:, 0]], 1) / np.linalg.norm(arm, axis=1)[:, None]
    # the normal is square to the tangent: sin(angle between tangent and direction) = cos phi
    expected = np.arcsin(np.clip(np.abs(np.einsum("ij,ij->i", tangent, direction)), 0, 1))
    assert np.abs(np.abs(np.asarray(body["pressure_angle"])) - expected).max() < 1e-5


def test_pressure_angle_and_curvature_are_nortons_formulas() -> None:
    """Translating roller: phi = arctan((s' - e) / (sqrt(R_p^2 - e^2) + s)) (Norton eq. 8.31);
    without offset rho_pitch = ((R_p + s)^2 + s'^2)^1.5 / ((R_p + s)^2 + 2 s'^2 - (R_p + s) s'')
    (eq. 8.33); flat face: rho = R_b + s + s'' (eq. 8.37); to 1e-12 relative."""
    theta = np.linspace(0.0, 2.0 * math.pi, 997, endpoint=False)
    offset = parse_cam(scene())
    g = cam_geometry(offset, theta)
    lift = g.lift
    rp, e = 0.05, 0.005
    phi = np.arctan((lift.ds - e) / (math.sqrt(rp**2 - e**2) + lift.s))
    assert g.pressure_angle == pytest.approx(phi, rel=1e-12, abs=1e-14)
    centred = dict(ROLLER, offset=0.0)
    g = cam_geometry(parse_cam(scene(follower=centred)), theta)
    y = rp + lift.s
    rho = (y**2 + lift.ds**2) ** 1.5 / (y**2 + 2 * lift.ds**2 - y * lift.d2s)
    assert g.pitch_radius == pytest.approx(rho, rel=1e-12)
    assert g.radius == pytest.approx(rho - 0.01, rel=1e-12)
    g = cam_geometry(parse_cam(scene(follower=FLAT)), theta)
    assert g.radius == pytest.approx(0.04 + lift.s + lift.d2s, rel=1e-12)
    assert not g.pressure_angle.any()


@pytest.mark.parametrize("name", sorted(FOLLOWERS))
def test_radius_of_curvature_against_the_profile(name: str) -> None:
    """rho of the cam surface equals the profile's radius of curvature by finite differences
    (4-5-6-7 laws: the jerk is continuous, so second differences converge), to 1e-5 relative,
    or near an inflection (|rho| of metres) 1/rho to 1e-5 of the largest curvature. The
    oscillating flat face lifts 0.15 rad: no undercut, so the profile never turns back."""
    follower, lift = FOLLOWERS[name]
    lift = min(lift, 0.15) if name == "oscillating_flat" else lift
    doc = scene("polynomial_4567", "polynomial_4567", follower=follower, lift=lift)
    body = solver.sweep(doc, 20000)
    theta = np.asarray(body["cam_angle"])
    profile = np.asarray(body["profile"])
    step = theta[1] - theta[0]
    d1 = _profile_derivative(profile, theta)
    d2 = (np.roll(profile, -1, 0) - 2 * profile + np.roll(profile, 1, 0)) / step**2
    curvature = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
    # a counter-clockwise cam's profile is traced clockwise: convex is negative here
    rho = np.asarray(body["radius_of_curvature"], dtype=float)
    by_radius = np.abs(-1.0 / curvature - rho) <= 1e-5 * np.abs(rho)
    by_curvature = np.abs(-curvature - 1.0 / rho) <= 1e-5 * np.abs(1.0 / rho).max()
    assert np.all(by_radius | by_curvature)


# --- warnings ------------------------------------------------------------------------------------


def test_a_harmonic_rise_into_a_dwell_breaks_the_fundamental_law() -> None:
    """Harmonic: y'' = pi^2/2 at both ends, so the acceleration jumps from -pi^2 h omega^2 /
    (2 beta^2) to 0 entering the dwell at 120 deg and from 0 to +that at 0 deg."""
    warnings = solver.sweep(scene("harmonic", "cycloidal"), 36).warnings
    jump = math.pi**2 / 2 * H * OMEGA**2 / math.radians(BETA_DEG) ** 2
    assert len(warnings) == 2, warnings
    assert warnings[0].startswith(
        "discontinuous acceleration at cam angle 120 deg between segments[0] (rise, harmonic)"
        f" and segments[1] (dwell): a jumps from {-jump:.6g} to 0 m/s^2, an infinite jerk"
    )
    entering = "between segments[3] (dwell) and segments[0] (rise, harmonic)"
    assert warnings[1].startswith(f"discontinuous acceleration at cam angle 0 deg {entering}")
    assert solver.sweep(scene("cycloidal", "modified_sine"), 36).warnings == ()
    uniform = solver.sweep(scene("uniform", "polynomial_345"), 36).warnings
    assert [w.split(" at ")[0] for w in uniform] == ["discontinuous velocity"] * 2


def _radius_of(sentence: str) -> float:
    return float(sentence.split("a base radius of at least ")[1].split(" m")[0])


def test_pressure_angle_warning_and_its_cure() -> None:
    """A small cam with a knife follower: phi > 30 deg; the base radius offered brings the
    largest |phi| within 30 deg, and 1 % less does not."""
    doc = scene("cycloidal", "cycloidal", follower={"motion": "translating", "contact": "knife"},
                base_radius=0.02)  # fmt: skip
    (warning,) = solver.sweep(doc, 36).warnings
    assert warning.startswith("pressure angle ") and "above 30 deg for a translating" in warning
    cure = _radius_of(warning)

    def worst(radius: float) -> float:
        g = cam_geometry(parse_cam(dict(doc, cam={"base_radius": radius, "omega": OMEGA})),
                         np.linspace(0, 2 * math.pi, 7200, endpoint=False))  # fmt: skip
        return math.degrees(float(np.abs(g.pressure_angle).max()))

    assert worst(cure) <= 30.0 < worst(0.99 * cure)


def test_undercut_warnings_and_their_cures() -> None:
    """A roller larger than the pitch curve's sharpest convex radius, and a flat face on too
    small a base circle: the flat face's cure is max(-(s + s'')) (rho = R_b + s + s'' >= 0)."""
    roller = {"motion": "translating", "contact": "roller", "roller_radius": 0.02}
    doc = scene("cycloidal", "cycloidal", base_radius=0.02, lift=0.03, follower=roller)
    for i, duration in enumerate([40, 0.5, 40, 279.5]):  # a steep rise and return
        doc["segments"][i]["duration_deg"] = duration
    warnings = solver.sweep(doc, 36).warnings
    undercut = [w for w in warnings if w.startswith("undercutting")]
    assert len(undercut) == 1 and "less than the roller radius 0.02 m" in undercut[0]
    cure = _radius_of(undercut[0])
    theta = np.linspace(0, 2 * math.pi, 7200, endpoint=False)

    def tight(radius: float) -> bool:
        g = cam_geometry(parse_cam(dict(doc, cam={"base_radius": radius, "omega": OMEGA})), theta)
        assert g.pitch_radius is not None
        return bool(((g.pitch_radius > 0) & (g.pitch_radius < 0.02)).any())

    assert not tight(cure) and tight(0.99 * cure)
    flat = scene("cycloidal", "cycloidal", follower=FLAT, base_radius=0.005, lift=0.04)
    (warning,) = solver.sweep(flat, 36).warnings
    assert warning.startswith("undercutting: the cam surface's radius of curvature is -")
    lift = follower_lift(parse_cam(flat), theta)
    assert _radius_of(warning) == pytest.approx(float(np.max(-(lift.s + lift.d2s))), rel=1e-3)


# --- the scene -----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d["segments"].pop(), "segments: the durations sum to 120 + 60 + 120 = 300 deg, "
         "not 360 deg"),
        (lambda d: d["segments"][2].update(lift=0.02), "segments: the rises lift the follower "
         "0.025 m and the returns lower it 0.02 m"),
        (lambda d: d["follower"].update(offset=0.06), "follower.offset: |e| = 0.06 m is not less "
         "than the prime circle radius R_b + r = 0.05 m"),
        (lambda d: d["cam"].update(omega=0), "cam.omega: must not be 0"),
        (lambda d: d["segments"][0].update(law="parabolic"), "segments[0].law: expected one of "
         "uniform, harmonic, cycloidal"),
        (lambda d: d["segments"][1].update(lift=0.01), "segments[1].lift: a dwell has no law"),
        (lambda d: d["cam"].update(base_radius=-1), "cam.base_radius: must be positive, got -1"),
        (lambda d: d["follower"].pop("roller_radius"), "follower.roller_radius: is required"),
    ],
)  # fmt: skip
def test_invalid_scenes_state_the_numbers(change: Any, message: str) -> None:
    doc = copy.deepcopy(scene())
    change(doc)
    with pytest.raises(solver.InvalidScene) as raised:
        solver.sweep(doc, 36)
    assert str(raised.value).startswith(message)


def test_a_clockwise_cam_is_the_mirror_image() -> None:
    """omega < 0 with offset e: the profile of omega > 0 with offset -e, mirrored in y."""
    ccw = solver.sweep(scene(follower=dict(ROLLER, offset=-0.005)), 90)
    cw = solver.sweep(scene(omega=-OMEGA), 90)
    assert np.asarray(cw["profile"]) == pytest.approx(np.asarray(ccw["profile"]) * [-1, 1])
    assert np.asarray(cw["pressure_angle"]) == pytest.approx(np.asarray(ccw["pressure_angle"]))


def test_analyze_at_an_angle_is_the_sweeps_sample() -> None:
    doc = scene(follower=OSCILLATING, lift=ANGULAR_LIFT)
    swept = solver.sweep(doc, 360)
    one = solver.analyze(doc, angle_deg=60.0 + 360.0)
    assert one["cam_angle"] == pytest.approx(math.radians(60.0))
    assert one["segment"] == 0
    for key in ("displacement", "velocity", "acceleration", "jerk"):
        assert one["follower"][key] == pytest.approx(swept["follower"][key][60], rel=1e-12)
    assert one["pressure_angle"] == pytest.approx(swept["pressure_angle"][60], rel=1e-12)
    assert one["contact_point"] == pytest.approx(list(swept["contact_point"][60]), rel=1e-12)
    assert one.as_dict()["warnings"] == list(swept.warnings)
