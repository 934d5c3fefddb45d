"""Full force balancing of a four-bar with one counterweight on each link that turns about the
ground (the seed 004 method), in complex numbers (x + iy) at the drawn pose.

The coupler A-B (mass m_c, first moment S_c = sum m (r - A)) is statically equivalent to
(m_c - Q) at A and Q at B with Q = S_c / (B - A), a complex number that does not change as the
coupler turns. The centre of mass stays put when the crank's side and the rocker's side each have
their first moment about their pivot at zero:

    S_1 + (m_c - Q)(A - O) + m_k (K - O) = 0,     S_3 + Q (B - Gamma) + m_l (L - Gamma) = 0

(S_1, S_3: the crank's and the rocker's own first moments about O and Gamma), and then

    r_G = [(M_1 + m_k + m_c - Q) O + (M_3 + m_l + Q) Gamma] / M.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from solver.errors import InvalidScene
from solver.model.scene import LinkageScene


@dataclass(frozen=True)
class Counterweight:
    """Where a counterweight goes: ``distance`` from the pivot along the link's direction at the
    drawn pose (first point to second), ``offset`` across it (counter-clockwise), ``position``."""

    link: str
    mass: float
    pivot: str
    distance: float
    offset: float
    position: tuple[float, float]


@dataclass(frozen=True)
class Balance:
    counterweights: tuple[Counterweight, ...]
    center_of_mass: tuple[float, float]
    mass: float
    scene: dict[str, Any]


@dataclass(frozen=True)
class _Side:
    link: str
    pivot: str  # the revolute joint with the ground
    pin: str  # the revolute joint with the coupler


def _four_bar(scene: LinkageScene) -> tuple[_Side, _Side, str]:
    """The crank's and the rocker's sides and the coupler, or why this is not a four-bar."""
    moving = scene.moving_links
    revolute = all(j.type == "revolute" for j in scene.joints)
    if len(moving) != 3 or len(scene.joints) != 4 or not revolute:
        raise InvalidScene(
            "balance: only a four-bar (three moving links, four revolute joints) can be balanced "
            f"this way; this linkage has {len(moving)} moving links and {len(scene.joints)} joints"
        )
    grounded = {
        (set(j.links) - {scene.ground}).pop(): j.point
        for j in scene.joints
        if scene.ground in j.links
    }
    coupler = [link for link in moving if link not in grounded]
    if len(grounded) != 2 or len(coupler) != 1:
        raise InvalidScene("balance: a four-bar has two links that turn about the ground")
    sides = []
    for link, pivot in grounded.items():
        pin = next((j.point for j in scene.joints if set(j.links) == {link, coupler[0]}), None)
        if pin is None:
            raise InvalidScene(f"balance: link '{link}' is not jointed to the coupler")
        sides.append(_Side(link, pivot, pin))
    first = scene.drivers[0].link if scene.drivers else sides[0].link
    crank, rocker = sorted(sides, key=lambda s: s.link != first)
    return crank, rocker, coupler[0]


def _mass_and_moment(scene: LinkageScene, link: str, about: complex) -> tuple[float, complex]:
    """The link's mass and its first moment sum m (r - about) at the drawn pose."""
    assert scene.dynamics is not None
    bodies, points = scene.dynamics.masses_of(link)
    if not bodies:
        raise InvalidScene(f"masses.{link}: balancing needs the mass of every moving link")
    mass, moment = 0.0, 0j
    for body in bodies:
        mass += body.mass
        moment += body.mass * (complex(*body.center) - about)
    for pm in points:
        mass += pm.mass
        moment += pm.mass * (complex(*scene.points[pm.point]) - about)
    return mass, moment


def balance_four_bar(
    scene: LinkageScene, doc: Mapping[str, Any], counterweights: Sequence[tuple[str, float]]
) -> Balance:
    """Counterweights (link, mass) on the crank and the rocker that keep the centre of mass
    still, and ``doc`` with them as point masses (a new point on each link where none is)."""
    if scene.dynamics is None:
        raise InvalidScene("masses: balancing needs the mass of every moving link")
    crank, rocker, coupler = _four_bar(scene)
    given = {}
    for i, (link, mass) in enumerate(counterweights):
        if link not in (crank.link, rocker.link):
            raise InvalidScene(
                f"counterweights[{i}].link: '{link}' does not turn about the ground; put one "
                f"counterweight on '{crank.link}' and one on '{rocker.link}'"
            )
        if link in given:
            raise InvalidScene(f"counterweights[{i}].link: a second counterweight on '{link}'")
        if not (math.isfinite(mass) and mass > 0):
            raise InvalidScene(f"counterweights[{i}].mass: must be positive, got {mass:g}")
        given[link] = mass
    if len(given) != 2:
        raise InvalidScene(
            f"counterweights: one on '{crank.link}' and one on '{rocker.link}' are needed"
        )

    def at(point: str) -> complex:
        return complex(*scene.points[point])

    A, B = at(crank.pin), at(rocker.pin)
    m_c, S_c = _mass_and_moment(scene, coupler, A)
    Q = S_c / (B - A)
    placed = []
    total = m_c
    center = 0j
    for side, share in ((crank, m_c - Q), (rocker, Q)):
        pivot = at(side.pivot)
        own_mass, own_moment = _mass_and_moment(scene, side.link, pivot)
        mass = given[side.link]
        K = pivot - (own_moment + share * (at(side.pin) - pivot)) / mass
        ends = scene.links[side.link].points
        u = at(ends[1]) - at(ends[0])
        u /= abs(u)
        along = (K - pivot) / u
        placed.append(
            Counterweight(side.link, mass, side.pivot, along.real, along.imag, (K.real, K.imag))
        )
        total += own_mass + mass
        center += (own_mass + mass + share) * pivot
    center /= total
    return Balance(
        tuple(placed), (center.real, center.imag), total, _with_counterweights(scene, doc, placed)
    )


def _with_counterweights(
    scene: LinkageScene, doc: Mapping[str, Any], placed: Sequence[Counterweight]
) -> dict[str, Any]:
    """``doc`` with each counterweight as a point mass, at a new point of its link named as the
    textbook names them, K on the crank and L on the rocker (or at the link's point that is
    already there), the masses mK and mL."""
    out = copy.deepcopy(dict(doc))
    out["point_masses"] = list(out.get("point_masses", []))
    names = {pm["name"] for pm in out["point_masses"] if isinstance(pm, Mapping) and "name" in pm}
    for w, letter in zip(placed, ("K", "L"), strict=True):
        K = complex(*w.position)
        near = [
            p
            for p in scene.links[w.link].points
            if abs(complex(*scene.points[p]) - K) <= 1e-9 * scene.size
        ]
        point = near[0] if near else _fresh(letter, out["points"])
        if not near:
            out["points"][point] = [K.real, K.imag]
            out["links"][w.link] = {
                **out["links"][w.link],
                "points": [*out["links"][w.link]["points"], point],
            }
        name = _fresh(f"m{letter}", names)
        names.add(name)
        out["point_masses"].append({"name": name, "link": w.link, "point": point, "mass": w.mass})
    out["title"] = f"{doc.get('title') or 'four-bar'}, balanced"[:200]
    return out


def _fresh(name: str, used: Any) -> str:
    candidate, k = name, 1
    while candidate in used:
        k += 1
        candidate = f"{name}_{k}"
    return candidate
