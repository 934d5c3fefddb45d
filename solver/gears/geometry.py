"""Where a gear train's axes are: the pitch circles on the module and the mounts.

Every gear's pitch radius is r = m N / 2. Two meshing gears' axes are a centre distance apart,
a = m (N_a + N_b) / 2 for an external pair, a = m (N_ring - N_pinion) / 2 for an annulus and its
pinion, in the body that holds both axes (the frame, or the carrier of a planet). A gear on the
frame that meshes with a planet turns about the planet's carrier's axis (else the mesh would
part as the carrier turns), and the members of one shaft share an axis: so a sun and a ring on
one carrier's axis fix its planet's distance twice, which must agree (N_ring = N_sun + 2 N_planet
for a simple planetary train). ``check_pitch_circles`` places every axis from its meshes and
reports, with the numbers, a mesh whose pitch circles cannot touch; ``layout`` gives the places
(each member's axis at t = 0, carriers at angle 0).

Two meshing gears on one axis cannot touch on any module; that is checked always. The distances
are checked with a ``module``: without one, each mesh may be cut on its own module and only the
tooth ratios count.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from solver.errors import InvalidScene
from solver.gears.scene import GearTrainScene, Mesh

DISTANCE_TOLERANCE = 1e-9  # relative: centre distances that agree to rounding
TRIAL_ANGLES = 24  # directions tried for an axis placed by one mesh (the farthest from the rest)

Point = tuple[float, float]


@dataclass(frozen=True)
class Layout:
    """Each gear's ``pitch_radius`` (m) and each member's ``centre`` (m): its axis at t = 0 in
    the frame, a planet's with its carrier at angle 0."""

    pitch_radius: Mapping[str, float]
    centre: Mapping[str, Point]


def pitch_radius(module: float, teeth: int) -> float:
    """r = m N / 2."""
    return module * teeth / 2.0


def centre_distance(scene: GearTrainScene, mesh: Mesh, module: float) -> float:
    """a = m (N_a + N_b) / 2 external, a = m (N_ring - N_pinion) / 2 internal."""
    a, b = (scene.gear(name) for name in mesh.gears)
    if mesh.internal:
        return module * abs(a.teeth - b.teeth) / 2.0
    return module * (a.teeth + b.teeth) / 2.0


def _formula(scene: GearTrainScene, mesh: Mesh, module: float) -> str:
    a, b = (scene.gear(name) for name in mesh.gears)
    if mesh.internal:
        ring, pinion = (a, b) if a.internal else (b, a)
        return (
            f"m (N_{ring.name} - N_{pinion.name}) / 2 = {module:g} ({ring.teeth} - "
            f"{pinion.teeth}) / 2 = {centre_distance(scene, mesh, module):.6g} m"
        )
    return (
        f"m (N_{a.name} + N_{b.name}) / 2 = {module:g} ({a.teeth} + {b.teeth}) / 2 = "
        f"{centre_distance(scene, mesh, module):.6g} m"
    )


def axes(scene: GearTrainScene) -> dict[str, str]:
    """Each member's axis, named by one member on it: the shafts' members share one, and a gear
    on the frame meshing with a planet turns about the planet's carrier's axis."""
    parent = {name: name for name in scene.members}

    def find(name: str) -> str:
        while parent[name] != name:
            parent[name] = parent[parent[name]]
            name = parent[name]
        return name

    def union(a: str, b: str) -> None:
        parent[find(a)] = find(b)

    for shaft in scene.shafts:
        for name in shaft[1:]:
            union(name, shaft[0])
    for mesh in scene.meshes:
        if mesh.carrier is not None:
            for name in mesh.gears:
                if scene.mount(name) is None:
                    union(name, mesh.carrier)
    return {name: find(name) for name in scene.members}


def _coaxial(scene: GearTrainScene, axis: Mapping[str, str]) -> None:
    for i, mesh in enumerate(scene.meshes):
        a, b = mesh.gears
        if axis[a] == axis[b]:
            shared = [m for m in scene.members if axis[m] == axis[a] and m not in (a, b)]
            why = "turn about one axis" + (f" (with {', '.join(shared)})" if shared else "")
            raise InvalidScene(
                f"meshes[{i}]: {a} and {b} {why}, so their pitch circles cannot touch: the mesh "
                "needs their axes apart by the sum (an annulus: the difference) of the pitch "
                "radii"
            )


def _direction(points: Mapping[str, Point], around: Point, radius: float) -> Point:
    """The point ``radius`` from ``around`` farthest from every point placed so far."""
    best, best_gap = (around[0] + radius, around[1]), -1.0
    for k in range(TRIAL_ANGLES):
        angle = 2.0 * math.pi * k / TRIAL_ANGLES
        trial = (around[0] + radius * math.cos(angle), around[1] + radius * math.sin(angle))
        gap = min((math.dist(trial, p) for p in points.values()), default=math.inf)
        if gap > best_gap + 1e-12:
            best, best_gap = trial, gap
    return best


def _neighbours(
    edges: list[tuple[int, str, str, float]], name: str
) -> list[tuple[int, str, float]]:
    """(mesh index, the other axis, distance) of every edge at ``name``."""
    return [(i, q if p == name else p, d) for i, p, q, d in edges if name in (p, q)]


def _place_body(
    scene: GearTrainScene,
    module: float,
    points: list[str],
    edges: list[tuple[int, str, str, float]],
    origin: tuple[str, Point] | None,
) -> dict[str, Point]:
    """Place ``points`` (axes of one body) so that every edge (mesh index, p, q, distance) holds;
    ``origin`` fixes one of them (a carrier's axis)."""
    placed: dict[str, Point] = dict([origin]) if origin else {}
    by: dict[str, list[int]] = {p: [] for p in points}  # the meshes that placed each axis
    done: set[int] = set()
    while len(placed) < len(points):
        waiting = [n for n in points if n not in placed]
        name = max(
            waiting, key=lambda n: sum(1 for _, o, _ in _neighbours(edges, n) if o in placed)
        )
        known = [k for k in _neighbours(edges, name) if k[1] in placed]
        if not known:
            # A part of the train no mesh ties to the rest: beside it, for the drawing.
            right = max((x for x, _ in placed.values()), default=None)
            gap = 4.0 * module * max(g.teeth for g in scene.gears)
            placed[name] = (0.0, 0.0) if right is None else (right + gap, 0.0)
            continue
        i, other, d = known[0]
        by[name] = [i]
        others = [k for k in known if k[1] != other]
        if others:
            j, second, e = others[0]
            p1, p2 = placed[other], placed[second]
            span = math.dist(p1, p2)
            if (
                span > (d + e) * (1 + DISTANCE_TOLERANCE)
                or span < abs(d - e) * (1 - DISTANCE_TOLERANCE) - DISTANCE_TOLERANCE * span
            ):
                raise InvalidScene(
                    f"meshes[{i}] and meshes[{j}]: {name}'s axis must be {d:.6g} m from "
                    f"{other}'s axis ({_formula(scene, scene.meshes[i], module)}) and {e:.6g} m "
                    f"from {second}'s ({_formula(scene, scene.meshes[j], module)}), which are "
                    f"{span:.6g} m apart: no point is (it needs {abs(d - e):.6g} m <= "
                    f"{span:.6g} m <= {d + e:.6g} m), so the pitch circles cannot touch on "
                    "this module and these mounts"
                )
            along = (d * d - e * e + span * span) / (2.0 * span)
            height = math.sqrt(max(d * d - along * along, 0.0))
            ux, uy = (p2[0] - p1[0]) / span, (p2[1] - p1[1]) / span
            base = (p1[0] + along * ux, p1[1] + along * uy)
            placed[name] = (base[0] - height * uy, base[1] + height * ux)
            done.add(j)
            by[name].append(j)
        else:
            placed[name] = _direction(placed, placed[other], d)
        done.add(i)
        for k, p, q, need in edges:
            if k in done or p not in placed or q not in placed:
                continue
            done.add(k)
            apart = math.dist(placed[p], placed[q])
            if abs(apart - need) > DISTANCE_TOLERANCE * need:
                earlier = sorted({*by.get(p, []), *by.get(q, [])} - {k})
                told = ", ".join(f"meshes[{m}]" for m in earlier) or "the mounts"
                a, b = scene.meshes[k].gears
                raise InvalidScene(
                    f"meshes[{k}]: the pitch circles of {a} and {b} cannot touch on module "
                    f"{module:g} m and these mounts: the mesh needs their axes "
                    f"{_formula(scene, scene.meshes[k], module)} apart, but {told} already put "
                    f"them {apart:.6g} m apart"
                )
    return placed


@functools.lru_cache(maxsize=64)  # parsing checks it, analysing uses it: one scene, once
def check_pitch_circles(scene: GearTrainScene) -> Layout | None:
    """Check that every mesh's pitch circles can touch (see the module) and return the layout
    (None without a module)."""
    axis = axes(scene)
    _coaxial(scene, axis)
    module = scene.module
    if module is None:
        return None
    bodies: dict[str | None, list[str]] = {None: []}
    for carrier in scene.carriers:
        bodies[carrier] = [axis[carrier]]
    for name in scene.members:
        body = scene.mount(name)
        if axis[name] not in bodies.setdefault(body, []):
            bodies[body].append(axis[name])
    places: dict[str | None, dict[str, Point]] = {}
    for body in [None, *scene.carriers]:  # the frame first: it places the carriers' axes
        edges = [
            (i, axis[m.gears[0]], axis[m.gears[1]], centre_distance(scene, m, module))
            for i, m in enumerate(scene.meshes)
            if m.carrier == body
        ]
        origin = None if body is None else (axis[body], (0.0, 0.0))
        places[body] = _place_body(scene, module, bodies[body], edges, origin)
    centre: dict[str, Point] = {}
    for name in scene.members:
        body = scene.mount(name)
        x, y = places[body][axis[name]]
        if body is not None:
            cx, cy = places[None][axis[body]]
            x, y = x + cx, y + cy
        centre[name] = (x, y)
    radii = {g.name: pitch_radius(module, g.teeth) for g in scene.gears}
    return Layout(MappingProxyType(radii), MappingProxyType(centre))
