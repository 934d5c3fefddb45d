"""Textbook mechanisms as generators of scene-v1 ``linkage`` documents.

A preset turns a few named parameters (SI units, angles in degrees) into a JSON-ready document
drawn at the given crank angle: the four-bar, the slider-crank, the inverted slider-crank, the
crank-and-slotted-lever quick-return and the slider with a coupler extension. The pose is found in
closed form: every point is the crank pin, the intersection of two circles or of a circle with a
line, a point fixed in a link's frame, and a slotted lever's direction is that of its slot through
the pin (the solver's own dyads: ``groups.intersect``, ``rpr.slotted_lever``); ``assembly``
picks one of two mirror branches. Planar vectors are complex numbers here (x + iy),
so a turn by 90 degrees is a product with ``1j``.
"""

from __future__ import annotations

import cmath
import inspect
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np

from solver.errors import InvalidScene, NotAssemblable
from solver.kinematics.rigid import PointMotion
from solver.position.groups import intersect
from solver.position.groups.loci import Circle, Line, Locus
from solver.position.groups.rpr import slotted_lever

MIN_LENGTH = 1e-4  # m
MAX_LENGTH = 1e4  # m
MAX_OMEGA = 1e4  # rad/s
MAX_ALPHA = 1e6  # rad/s^2
# A distance may exceed the reach of two links by this relative amount (rounding at a toggle).
CLOSURE_TOLERANCE = 1e-12
# A coupler point closer than this fraction of the drawing's size to B or C is that joint: left out.
COINCIDENT = 1e-6


@dataclass(frozen=True)
class PresetParameter:
    """One named input of a preset: its default, unit, bounds and, for a choice, allowed values."""

    name: str
    default: float
    unit: str  # "m", "deg", "rad/s", "rad/s^2", or "" for a choice
    description: str
    minimum: float | None = None
    maximum: float | None = None
    choices: tuple[float, ...] | None = None
    labels: tuple[str, ...] | None = None  # one word per choice, for a selector

    def check(self, value: float) -> float:
        """The value as a float, or ``InvalidScene`` saying why it is not allowed."""
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise InvalidScene(f"{self.name}: expected a number, got {value!r}") from None
        unit = f" {self.unit}" if self.unit else ""
        if not math.isfinite(number):
            raise InvalidScene(f"{self.name} must be a finite number, got {number}")
        if self.choices is not None and number not in self.choices:
            allowed = ", ".join(f"{c:g}" for c in self.choices)
            raise InvalidScene(f"{self.name} = {number:g} is not one of {allowed}")
        low = -math.inf if self.minimum is None else self.minimum
        high = math.inf if self.maximum is None else self.maximum
        if not low <= number <= high:
            raise InvalidScene(
                f"{self.name} = {number:g}{unit} is outside the range [{low:g}, {high:g}]{unit}"
            )
        return number


Geometry = Callable[[Mapping[str, float]], dict[str, Any]]


@dataclass(frozen=True)
class Preset:
    """A textbook mechanism type: its parameters and the generator of its scene document."""

    name: str
    title: str
    description: str
    parameters: tuple[PresetParameter, ...]
    geometry: Geometry = field(repr=False, compare=False)

    def resolve(self, values: Mapping[str, float]) -> dict[str, float]:
        """Every parameter's value: the given one checked, or its default."""
        allowed = [p.name for p in self.parameters]
        unknown = sorted(set(values) - set(allowed))
        if unknown:
            raise InvalidScene(
                f"unknown parameter(s) {', '.join(unknown)} for preset '{self.name}'; "
                f"allowed: {', '.join(allowed)}"
            )
        return {p.name: p.check(values.get(p.name, p.default)) for p in self.parameters}

    def build(self, values: Mapping[str, float]) -> dict[str, Any]:
        """The scene-v1 ``linkage`` document drawn at the given crank angle.

        Missing values take their defaults. Raises ``InvalidScene`` for an unknown parameter or a
        value out of range, ``NotAssemblable`` (with the numbers) when the links cannot close.
        """
        v = self.resolve(values)
        return {
            "kind": "linkage",
            "title": self.title,
            **self.geometry(v),
            "drivers": [{"link": "crank", "omega": v["omega"], "alpha": v["alpha"]}],
        }


# --- geometry ------------------------------------------------------------------------------------


def _circle_circle(
    p: complex,
    r_p: float,
    q: complex,
    r_q: float,
    *,
    left: bool,
    names: tuple[str, str, str],
    where: str,
) -> complex:
    """The point X with |X - p| = r_p and |X - q| = r_q, to the left of p -> q if ``left``
    (the solver's RRR dyad, ``groups.intersect``).

    With d = |q - p| the circles meet where |r_p - r_q| <= d <= r_p + r_q (within
    ``CLOSURE_TOLERANCE``). ``names`` = (PQ, r_p, r_q) name the distance and the two radii in the
    error message.
    """
    pq, rp, rq = names
    d = abs(q - p)
    if d > (r_p + r_q) * (1 + CLOSURE_TOLERANCE):
        raise NotAssemblable(f"|{pq}| = {d:.6g} m > {rp} + {rq} = {r_p + r_q:.6g} m {where}")
    if d < abs(r_p - r_q) * (1 - CLOSURE_TOLERANCE) or d == 0:
        raise NotAssemblable(f"|{pq}| = {d:.6g} m < |{rp} - {rq}| = {abs(r_p - r_q):.6g} m {where}")
    return _dyad_point(Circle(_fixed(p), r_p, "p", rp), Circle(_fixed(q), r_q, "q", rq), left)


def _circle_line(
    c: complex,
    r: float,
    q: complex,
    u: complex,
    *,
    forward: bool,
    names: tuple[str, str, str],
    where: str,
) -> complex:
    """The point X on the line q + s u (|u| = 1) with |X - c| = r, further along u if ``forward``
    (the solver's RRP dyad, ``groups.intersect``).

    They meet where the distance Im((c - q) conj(u)) from the line to c is at most r (within
    ``CLOSURE_TOLERANCE``). ``names`` = (C, line, r) name the centre, the line and the radius in
    the error message.
    """
    centre, line, radius = names
    distance = abs(((c - q) * u.conjugate()).imag)
    if distance > r * (1 + CLOSURE_TOLERANCE):
        raise NotAssemblable(
            f"the distance from {centre} to {line} is {distance:.6g} m > {radius} = "
            f"{r:.6g} m {where}"
        )
    slot = Line(_fixed(q), np.array([[u.real, u.imag]], dtype=float), None, None, line)
    return _dyad_point(Circle(_fixed(c), r, centre, radius), slot, forward)


def _fixed(z: complex) -> PointMotion:
    """The point z as the solver's one-sample position."""
    return PointMotion(np.array([[z.real, z.imag]]))


def _dyad_point(first: Locus, second: Locus, positive: bool) -> complex:
    """The branch X = base + sign h offset of the two loci (sign +1 if ``positive``)."""
    x = intersect(first, second, "X").point(np.array([1.0 if positive else -1.0]))
    return complex(x[0, 0], x[0, 1])


def _on_horizontal_guide(
    b: complex,
    length: float,
    height: float,
    link: str,
    where: str,
    *,
    forward: bool = True,
    guide: str = "the guide line",
) -> complex:
    """The point at distance ``length`` from B on the fixed horizontal guide y = ``height``
    (to the right of B when ``forward``)."""
    names = ("B", f"{guide} y = {height:g} m", link)
    return _circle_line(b, length, complex(0, height), 1, forward=forward, names=names, where=where)


def _slot_direction(
    pivot: complex, pin: complex, offset: float, *, names: str, where: str
) -> complex:
    """Unit direction u of a lever pivoted at ``pivot`` whose slot passes through ``pin`` (the
    solver's slotted lever, ``rpr.slotted_lever``).

    The slot is the line pivot + offset iu + s u (offset to the left of u), so with d = pin - pivot,
    u = exp(i beta), beta = arg d - atan2(offset, s), and the pin sits at s = sqrt(|d|^2 -
    offset^2) >= 0.
    """
    d = pin - pivot
    if abs(d) < abs(offset) or d == 0:
        raise NotAssemblable(
            f"|{names}| = {abs(d):.6g} m < |slot_offset| = {abs(offset):.6g} m {where}: "
            "the pin cannot reach the slot line"
        )
    lever = slotted_lever(_fixed(pivot), _fixed(pin), offset, np.array([1.0]), order=0)
    return cmath.exp(1j * float(lever.beta[0]))


def _at(origin: complex, unit: complex, along: float, left: float) -> complex:
    """The point at ``along`` in the direction ``unit`` from ``origin`` and ``left`` to its left."""
    return origin + complex(along, left) * unit


def _unit(frm: complex, to: complex) -> complex:
    return (to - frm) / abs(to - frm)


def _lever_along_slot(v: Mapping[str, float]) -> float:
    """How far along the slot line the lever's end lies, its distance from the pivot being
    ``lever``: sqrt(lever^2 - slot_offset^2)."""
    lever, offset = v["lever"], v["slot_offset"]
    if lever <= abs(offset):
        raise InvalidScene(
            f"lever = {lever:g} m must be longer than |slot_offset| = {abs(offset):g} m: "
            "its end lies on the slot line"
        )
    return math.sqrt(lever * lever - offset * offset)


def _crank_pin(pivot: complex, v: Mapping[str, float]) -> tuple[complex, str]:
    """The crank pin at ``crank_angle_deg`` and the phrase naming the angle for error messages."""
    angle = v["crank_angle_deg"]
    return pivot + cmath.rect(v["crank"], math.radians(angle)), f"at crank angle {angle:g} deg"


def _with_coupler_point(points: dict[str, complex], v: Mapping[str, float]) -> list[str]:
    """Add the coupler point P at (u, v) in the frame of B -> C; the coupler's point names.

    P is left out when it coincides with B or C (it would be that joint).
    """
    b, c = points["B"], points["C"]
    p = _at(b, _unit(b, c), v["coupler_point_u"], v["coupler_point_v"])
    xs, ys = [z.real for z in points.values()], [z.imag for z in points.values()]
    size = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    if min(abs(p - b), abs(p - c)) > COINCIDENT * size:
        points["P"] = p
        return ["B", "C", "P"]
    return ["B", "C"]


def _revolute(point: str, a: str, b: str) -> dict[str, Any]:
    return {"type": "revolute", "point": point, "links": [a, b]}


def _slider(point: str, guide: str, follower: str, axis: complex) -> dict[str, Any]:
    return {
        "type": "slider",
        "point": point,
        "links": [guide, follower],
        "axis": [float(axis.real), float(axis.imag)],
    }


def _layout(
    points: Mapping[str, complex],
    ground: Sequence[str],
    links: Mapping[str, Sequence[str]],
    joints: list[dict[str, Any]],
) -> dict[str, Any]:
    return {
        "points": {name: [float(z.real), float(z.imag)] for name, z in points.items()},
        "links": {
            "ground": {"points": list(ground), "ground": True},
            **{name: {"points": list(names)} for name, names in links.items()},
        },
        "joints": joints,
    }


# --- the presets ---------------------------------------------------------------------------------


def _four_bar(v: Mapping[str, float]) -> dict[str, Any]:
    """Four-bar linkage: the crank AB turns about the fixed pivot A, the coupler BC carries the
    coupler point P, and the rocker DC swings about the fixed pivot D.

    A is at the origin and D at (ground, 0). C is where the circle of radius `coupler` about B
    meets the circle of radius `rocker` about D: assembly 0 (open) takes C to the left of the line
    from B to D (above the ground line in the usual picture), 1 (crossed) its mirror image across
    BD. Grashof: if the shortest plus the longest link is at most the sum of the other two and the
    crank is the shortest, the crank turns all the way round (a crank-rocker). The defaults are a
    crank-rocker driven at 240 rpm.
    """
    a, d = 0j, complex(v["ground"], 0)
    b, where = _crank_pin(a, v)
    c = _circle_circle(
        b,
        v["coupler"],
        d,
        v["rocker"],
        left=v["assembly"] == 0,
        names=("BD", "coupler", "rocker"),
        where=where,
    )
    points = {"A": a, "B": b, "C": c, "D": d}
    coupler = _with_coupler_point(points, v)
    return _layout(
        points,
        ["A", "D"],
        {"crank": ["A", "B"], "coupler": coupler, "rocker": ["D", "C"]},
        [
            _revolute("A", "ground", "crank"),
            _revolute("B", "crank", "coupler"),
            _revolute("C", "coupler", "rocker"),
            _revolute("D", "rocker", "ground"),
        ],
    )


def _slider_crank(v: Mapping[str, float]) -> dict[str, Any]:
    """Slider-crank (the engine mechanism): the crank AB turns about the fixed pivot A, the
    connecting rod BC carries the coupler point P, and the piston pin C slides along the fixed
    horizontal guide line y = offset.

    A is at the origin. offset = 0 gives the centred slider-crank; otherwise it is offset and the
    forward and return strokes take different crank angles. C is where the circle of radius `rod`
    about B meets the guide line: assembly 0 puts the slider to the right of B, 1 to the left.
    """
    a = 0j
    b, where = _crank_pin(a, v)
    offset = v["offset"]
    c = _on_horizontal_guide(b, v["rod"], offset, "rod", where, forward=v["assembly"] == 0)
    points = {"A": a, "B": b, "C": c}
    coupler = _with_coupler_point(points, v)
    return _layout(
        points,
        ["A"],
        {"crank": ["A", "B"], "coupler": coupler},
        [
            _revolute("A", "ground", "crank"),
            _revolute("B", "crank", "coupler"),
            _slider("C", "ground", "coupler", 1),
        ],
    )


def _inverted_slider_crank(v: Mapping[str, float]) -> dict[str, Any]:
    """Inverted slider-crank: the crank OA turns about the fixed pivot O, and its pin A carries a
    block that slides in the slot of the lever CD, pivoted at the fixed point C.

    O is at the origin and C at (ground, 0). The slot is a straight line fixed in the lever, at
    the perpendicular distance slot_offset from C (to the left of the direction from C to D; 0 = the
    slot runs through C). D is the lever's end on the slot line, at distance `lever` from C. The
    block slides along a slot that itself turns, so the pin's acceleration has a Coriolis term
    2 omega_lever x v_rel. With crank < ground the lever oscillates; with crank > ground it turns
    round (Whitworth).
    """
    along = _lever_along_slot(v)
    o, c = 0j, complex(v["ground"], 0)
    a, where = _crank_pin(o, v)
    u = _slot_direction(c, a, v["slot_offset"], names="CA", where=where)
    d = _at(c, u, along, v["slot_offset"])
    return _layout(
        {"O": o, "A": a, "C": c, "D": d},
        ["O", "C"],
        {"crank": ["O", "A"], "lever": ["C", "D"]},
        [
            _revolute("O", "ground", "crank"),
            _revolute("C", "ground", "lever"),
            _slider("A", "lever", "crank", u),
        ],
    )


def _quick_return(v: Mapping[str, float]) -> dict[str, Any]:
    """Crank-and-slotted-lever quick-return (shaper): the crank O2A turns about the fixed pivot
    O2, its pin A slides in the slot of the lever O4B pivoted at O4 below O2, and the lever's end
    B drives the rod BC, whose end C (the ram) slides on the fixed horizontal guide y = ram_height.

    O2 is at the origin and O4 at (0, -ground). The slot is at the perpendicular distance
    slot_offset from O4 (to the left of the direction from O4 to B; 0 = through O4) and B is on it,
    at distance `lever` from O4. The ram C is to the right of B. With crank < ground the cutting
    stroke takes the larger share of the crank's turn, 360 - 2 acos(crank/ground) degrees for a
    slot through O4, and the return is quick.
    """
    along = _lever_along_slot(v)
    o2, o4 = 0j, complex(0, -v["ground"])
    a, where = _crank_pin(o2, v)
    u = _slot_direction(o4, a, v["slot_offset"], names="O4A", where=where)
    b = _at(o4, u, along, v["slot_offset"])
    c = _on_horizontal_guide(b, v["rod"], v["ram_height"], "rod", where, guide="the ram's guide")
    return _layout(
        {"O2": o2, "A": a, "O4": o4, "B": b, "C": c},
        ["O2", "O4"],
        {"crank": ["O2", "A"], "lever": ["O4", "B"], "rod": ["B", "C"]},
        [
            _revolute("O2", "ground", "crank"),
            _revolute("O4", "ground", "lever"),
            _slider("A", "lever", "crank", u),
            _revolute("B", "lever", "rod"),
            _slider("C", "ground", "rod", 1),
        ],
    )


def _slider_guide_extension(v: Mapping[str, float]) -> dict[str, Any]:
    """Slider with a coupler extension: the crank AB turns about the fixed pivot A; the coupler
    BCD is pinned to it at B, its point C slides along the fixed horizontal guide y = guide_height,
    and D is on the extension of BC beyond C, at distance `extension` from C.

    A is at the origin; C is to the right of B. The coupler's velocity pole lies on the
    perpendicular to the guide through C and on the line AB.
    """
    a = 0j
    b, where = _crank_pin(a, v)
    c = _on_horizontal_guide(b, v["coupler"], v["guide_height"], "coupler", where)
    d = _at(c, _unit(b, c), v["extension"], 0)
    return _layout(
        {"A": a, "B": b, "C": c, "D": d},
        ["A"],
        {"crank": ["A", "B"], "coupler": ["B", "C", "D"]},
        [
            _revolute("A", "ground", "crank"),
            _revolute("B", "crank", "coupler"),
            _slider("C", "ground", "coupler", 1),
        ],
    )


# --- parameters ----------------------------------------------------------------------------------


def _length(name: str, default: float, description: str) -> PresetParameter:
    return PresetParameter(name, default, "m", description, MIN_LENGTH, MAX_LENGTH)


def _coordinate(name: str, default: float, description: str) -> PresetParameter:
    return PresetParameter(name, default, "m", description, -MAX_LENGTH, MAX_LENGTH)


def _crank_angle(default: float) -> PresetParameter:
    return PresetParameter(
        "crank_angle_deg",
        default,
        "deg",
        "Angle of the crank at the drawn pose, from the +x axis, counter-clockwise positive.",
        -360.0,
        360.0,
    )


def _omega(default: float) -> PresetParameter:
    return PresetParameter(
        "omega",
        default,
        "rad/s",
        "Angular velocity of the crank, counter-clockwise positive (rpm = omega * 30 / pi).",
        -MAX_OMEGA,
        MAX_OMEGA,
    )


def _alpha(default: float = 0.0) -> PresetParameter:
    return PresetParameter(
        "alpha",
        default,
        "rad/s^2",
        "Angular acceleration of the crank, counter-clockwise positive (0 = constant speed).",
        -MAX_ALPHA,
        MAX_ALPHA,
    )


def _assembly(description: str, labels: tuple[str, str]) -> PresetParameter:
    return PresetParameter(
        "assembly", 0.0, "", description, 0.0, 1.0, choices=(0.0, 1.0), labels=labels
    )


def _coupler_point(u: float, v: float) -> tuple[PresetParameter, PresetParameter]:
    return (
        _coordinate("coupler_point_u", u, "Coupler point P: distance from B along the line B->C."),
        _coordinate(
            "coupler_point_v",
            v,
            "Coupler point P: distance from the line B->C, positive to its left. "
            "P is left out when it falls on B or C.",
        ),
    )


def _slot_offset(pivot: str) -> PresetParameter:
    return _coordinate(
        "slot_offset",
        0.0,
        f"Distance of the slot line from the lever pivot {pivot} (0 = through it).",
    )


def _preset(name: str, title: str, geometry: Geometry, *parameters: PresetParameter) -> Preset:
    description = inspect.cleandoc(geometry.__doc__ or "")
    return Preset(name, title, description, parameters, geometry)


_CRANK = "Length of the crank, from its fixed pivot to the crank pin."

PRESETS: Mapping[str, Preset] = MappingProxyType(
    {
        p.name: p
        for p in (
            _preset(
                "four_bar",
                "four-bar linkage",
                _four_bar,
                _length("ground", 1.0, "Distance AD between the fixed pivots (the ground link)."),
                _length("crank", 0.15, _CRANK + " (AB)"),
                _length("coupler", 1.0, "Length of the coupler BC."),
                _length("rocker", 0.55, "Length of the rocker DC."),
                _crank_angle(30.0),
                _assembly(
                    "0 = open (C to the left of B->D), 1 = crossed (C mirrored across BD).",
                    ("open", "crossed"),
                ),
                *_coupler_point(0.5, 0.2),
                _omega(8 * math.pi),
                _alpha(),
            ),
            _preset(
                "slider_crank",
                "slider-crank",
                _slider_crank,
                _length("crank", 0.1, _CRANK + " (AB)"),
                _length("rod", 0.35, "Length of the connecting rod BC (the coupler)."),
                _coordinate(
                    "offset", 0.05, "Height y of the slider's guide line above A (0 = centred)."
                ),
                _crank_angle(60.0),
                _assembly(
                    "0 = slider to the right of B, 1 = slider to the left of B.",
                    ("slider right of B", "slider left of B"),
                ),
                *_coupler_point(0.175, 0.1),
                _omega(10.0),
                _alpha(),
            ),
            _preset(
                "inverted_slider_crank",
                "inverted slider-crank",
                _inverted_slider_crank,
                _length("crank", 0.15, _CRANK + " (OA)"),
                _length(
                    "ground", 0.3, "Distance OC between the crank's and the lever's fixed pivots."
                ),
                _length("lever", 0.5, "Length of the slotted lever from its pivot C to its end D."),
                _slot_offset("C"),
                _crank_angle(45.0),
                _omega(10.0),
                _alpha(),
            ),
            _preset(
                "quick_return",
                "crank-and-slotted-lever quick-return",
                _quick_return,
                _length("crank", 0.1, _CRANK + " (O2A)"),
                _length("ground", 0.3, "Distance O2O4: the lever pivot O4 is this far below O2."),
                _length(
                    "lever", 0.6, "Length of the slotted lever from its pivot O4 to its end B."
                ),
                _length("rod", 0.2, "Length of the link BC from the lever's end to the ram."),
                _coordinate("ram_height", 0.3, "Height y of the ram's guide line above O2."),
                _slot_offset("O4"),
                _crank_angle(30.0),
                _omega(10.0),
                _alpha(),
            ),
            _preset(
                "slider_guide_extension",
                "slider with coupler extension",
                _slider_guide_extension,
                _length("crank", 0.3, _CRANK + " (AB)"),
                _length(
                    "coupler", 0.5, "Length BC of the coupler, from the crank pin to the slider."
                ),
                _length("extension", 0.4, "Distance CD from the slider to the coupler's end D."),
                _coordinate("guide_height", 0.24, "Height y of the slider's guide line above A."),
                _crank_angle(120.0),
                _omega(-4.0),
                _alpha(),
            ),
        )
    }
)


def build_preset(name: str, values: Mapping[str, float]) -> dict[str, Any]:
    """The scene-v1 ``linkage`` document of preset ``name`` with the given parameter values."""
    preset = PRESETS.get(name)
    if preset is None:
        raise InvalidScene(f"unknown preset '{name}'; available: {', '.join(PRESETS)}")
    return preset.build(values)


# --- masses and loads (dynamics-v1) --------------------------------------------------------------

# Each preset's output and the load it carries: a constant moment on a link, or a constant force
# at a point of a link, pointing along -x (a resistance to a slider moving to the right).
_LOADS: Mapping[str, tuple[str, str | None, str]] = {
    "four_bar": ("rocker", None, "Constant moment on the rocker (counter-clockwise positive)."),
    "slider_crank": ("coupler", "C", "Constant force on the slider C along -x."),
    "inverted_slider_crank": ("lever", None, "Constant moment on the lever (ccw positive)."),
    "quick_return": ("rod", "C", "Constant force on the ram C along -x (the cutting force)."),
    "slider_guide_extension": ("coupler", "C", "Constant force on the slider C along -x."),
}
_MASS_NOTE = (
    "Masses (dynamics-v1): with mass_per_length > 0 every moving link is a uniform bar between its "
    "first two points of that mass per metre; gravity acts along -y; load is a constant load on "
    "the output. With the defaults (all 0) the scene has no mass fields."
)


def _mass_parameters(load: str) -> tuple[PresetParameter, ...]:
    unit = "N m" if "moment" in load else "N"
    return (
        PresetParameter(
            "mass_per_length", 0.0, "kg/m", "Mass per metre of every moving link.", 0.0, 1e6
        ),
        PresetParameter("gravity", 0.0, "m/s^2", "Acceleration of gravity, along -y.", 0.0, 1e3),
        PresetParameter("load", 0.0, unit, load, -1e9, 1e9),
    )


def with_masses(doc: dict[str, Any], v: Mapping[str, float], output: str) -> dict[str, Any]:
    """``doc`` with uniform bars of ``mass_per_length``, gravity and the output's load."""
    name, point, _ = _LOADS[output]
    rho, g, load = v["mass_per_length"], v["gravity"], v["load"]
    if rho > 0:
        masses = {}
        for link, body in doc["links"].items():
            ends = body["points"][:2]
            if not body.get("ground") and len(ends) == 2:
                length = math.dist(doc["points"][ends[0]], doc["points"][ends[1]])
                masses[link] = {"mass": rho * length, "bar": ends}
        doc["masses"] = masses
    if g > 0:
        doc["gravity"] = [0.0, -g]
    if load != 0 and point is None:
        doc["torques"] = [{"name": "load", "link": name, "moment": repr(load)}]
    elif load != 0:
        doc["forces"] = [
            {"name": "load", "link": name, "point": point, "magnitude": repr(load),
             "direction_deg": 180.0, "relative_to": "world"}
        ]  # fmt: skip
    return doc


def _massive(preset: Preset) -> Preset:
    """The preset with the mass parameters (see ``_MASS_NOTE``)."""
    geometry = preset.geometry

    def build(v: Mapping[str, float]) -> dict[str, Any]:
        return with_masses(geometry(v), v, preset.name)

    return Preset(
        preset.name,
        preset.title,
        f"{preset.description}\n\n{_MASS_NOTE}",
        (*preset.parameters, *_mass_parameters(_LOADS[preset.name][2])),
        build,
    )


def _seed004(v: Mapping[str, float]) -> dict[str, Any]:
    """Seed 004, the Thessaloniki crank-rocker with a loaded arm: the crank OA (uniform bar)
    turns about O at 240 rpm, the coupler AB (uniform bar) drives member 3, a uniform bar from
    its pivot Gamma through B to its end D (length rocker + extension), with a point mass at D.

    O is at the origin and Gamma at (ground, 0); B lies above the line A-Gamma. phi3 is member 3's
    angle from +y, clockwise positive (the seed's convention): phi3 = pi/2 - angle(rocker). The
    force F_D acts at D perpendicular to Gamma-D, counter-clockwise about Gamma, with magnitude
    force_max (phi3 - phi3_c)/(phi3_min - phi3_c) while phi3 decreases from phi3_c = force_on_deg
    to its minimum phi3_min (where the crank and the coupler fold over: |OB| = coupler - crank or
    coupler + crank), and 0 otherwise. Gravity along -y. The seed's mean motor power is -1599.59 W
    (the force drives the rocker in its active stroke), not the 0.75 kW the seed reports.
    """
    o, gamma = 0j, complex(v["ground"], 0)
    a, where = _crank_pin(o, v)
    b = _circle_circle(
        a, v["coupler"], gamma, v["rocker"], left=True, names=("AGamma", "coupler", "rocker"),
        where=where,
    )  # fmt: skip
    d = gamma + (b - gamma) / abs(b - gamma) * (v["rocker"] + v["extension"])
    phi3_min = _least_phi3(o, gamma, v)
    phi3_c = math.radians(v["force_on_deg"])
    if not phi3_min < phi3_c:
        raise InvalidScene(
            f"force_on_deg = {v['force_on_deg']:g} deg must exceed the least phi3 of the cycle, "
            f"{math.degrees(phi3_min):.6g} deg"
        )
    phi3 = 'pi/2 - angle("rocker")'
    law = (
        f'where(omega("rocker") >= 0 and {phi3} < {phi3_c!r} and {phi3} > {phi3_min!r}, '
        f"{v['force_max']!r}*({phi3} - {phi3_c!r})/({phi3_min!r} - {phi3_c!r}), 0)"
    )
    doc = _layout(
        {"O": o, "A": a, "B": b, "Gamma": gamma, "D": d},
        ["O", "Gamma"],
        {"crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["Gamma", "B", "D"]},
        [
            _revolute("O", "ground", "crank"),
            _revolute("A", "crank", "coupler"),
            _revolute("B", "coupler", "rocker"),
            _revolute("Gamma", "ground", "rocker"),
        ],
    )
    doc["masses"] = {
        "crank": {"mass": v["crank_mass"], "bar": ["O", "A"]},
        "coupler": {"mass": v["coupler_mass"], "bar": ["A", "B"]},
        "rocker": {"mass": v["rocker_mass"], "bar": ["Gamma", "D"]},
    }
    doc["point_masses"] = [{"name": "mD", "link": "rocker", "point": "D", "mass": v["end_mass"]}]
    doc["gravity"] = [0.0, -v["gravity"]]
    doc["forces"] = [
        {"name": "F_D", "link": "rocker", "point": "D", "magnitude": law,
         "direction_deg": 90.0, "relative_to": "link"}
    ]  # fmt: skip
    return doc


def _least_phi3(o: complex, gamma: complex, v: Mapping[str, float]) -> float:
    """Seed 004's least phi3 over the cycle: B where the crank and the coupler fold over (|OB| =
    coupler - crank or coupler + crank), on the drawn side of the ground line; inf if neither
    fold assembles."""
    least = math.inf
    for reach in (v["coupler"] - v["crank"], v["coupler"] + v["crank"]):
        try:
            fold = _circle_circle(
                o, abs(reach), gamma, v["rocker"], left=True, names=("OGamma", "OB", "rocker"),
                where="at a fold of the crank and the coupler",
            )  # fmt: skip
        except NotAssemblable:
            continue
        least = min(least, math.atan2((fold - gamma).real, (fold - gamma).imag))
    return least


def _mass(name: str, default: float, description: str) -> PresetParameter:
    return PresetParameter(name, default, "kg", description, 0.0, 1e6)


PRESETS = MappingProxyType(
    {
        **{name: _massive(preset) for name, preset in PRESETS.items()},
        "seed004": _preset(
            "seed004",
            "seed 004: loaded crank-rocker (dynamics)",
            _seed004,
            _length("crank", 0.15, _CRANK + " (OA)"),
            _length("coupler", 1.0, "Length of the coupler AB."),
            _length("ground", 1.0, "Distance O-Gamma between the fixed pivots."),
            _length("rocker", 0.55, "Distance Gamma-B on member 3."),
            _length("extension", 0.15, "Distance B-D: member 3 goes on beyond B to its end D."),
            _crank_angle(0.0),
            _omega(8 * math.pi),
            _alpha(),
            _mass("crank_mass", 30.0, "Mass of the crank (a uniform bar)."),
            _mass("coupler_mass", 60.0, "Mass of the coupler (a uniform bar)."),
            _mass("rocker_mass", 60.0, "Mass of member 3 (a uniform bar from Gamma to D)."),
            _mass("end_mass", 90.0, "The point mass at D."),
            PresetParameter("force_max", 3000.0, "N", "The largest F_D.", 0.0, 1e9),
            PresetParameter(
                "force_on_deg", -10.0, "deg", "phi3_c: F_D grows from 0 here.", -180.0, 180.0
            ),
            PresetParameter("gravity", 9.81, "m/s^2", "Acceleration of gravity.", 0.0, 1e3),
        ),
    }
)
