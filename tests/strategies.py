"""Hypothesis strategies shared by the property tests.

``assemblable_presets()`` draws ``(preset name, parameter values)`` pairs that
``solver.teaching.presets.build_preset`` assembles, away from the singular poses where a property
test would be ill-conditioned: the four-bar's triangle BCD is never flat, a rod never stands
perpendicular to its guide, and a slotted lever's pin never passes close to the lever pivot. Values
are drawn from a valid pose rather than rejected, so hardly any draw is wasted.
"""

from __future__ import annotations

import cmath
import math
from collections.abc import Callable, Sequence

from hypothesis import assume
from hypothesis import strategies as st

from solver.teaching.presets import PRESETS, build_preset

PresetValues = tuple[str, dict[str, float]]

_scale = st.floats(0.1, 20.0)
_angle = st.floats(-180.0, 180.0)
_ratio = st.floats(0.1, 0.9) | st.floats(1.1, 3.0)  # crank / ground of a slotted lever, not 1
_branch = st.sampled_from([0.0, 1.0])


def _rates(draw: st.DrawFn) -> dict[str, float]:
    return {"omega": draw(st.floats(-50.0, 50.0)), "alpha": draw(st.floats(-100.0, 100.0))}


def _coupler_point(draw: st.DrawFn, coupler: float) -> dict[str, float]:
    return {
        "coupler_point_u": coupler * draw(st.floats(-1.0, 1.5)),
        "coupler_point_v": coupler * draw(st.floats(-1.0, 1.0)),
    }


def _guide_height(draw: st.DrawFn, pin_y: float, rod: float) -> float:
    """A guide line the rod of length ``rod`` from a pin at height ``pin_y`` reaches at a slant."""
    return pin_y + rod * draw(st.floats(-0.9, 0.9))


@st.composite
def _four_bar(draw: st.DrawFn) -> PresetValues:
    ground = draw(_scale)
    crank = ground * draw(st.floats(0.05, 1.5))
    angle = draw(_angle)
    bd = abs(ground - cmath.rect(crank, math.radians(angle)))
    assume(bd > 0.05 * ground)
    coupler = bd * draw(st.floats(0.3, 3.0))
    # rocker strictly inside the triangle inequality, so the triangle BCD is never flat
    low, high = abs(bd - coupler), bd + coupler
    rocker = low + (high - low) * draw(st.floats(0.1, 0.9))
    values = {"ground": ground, "crank": crank, "coupler": coupler, "rocker": rocker}
    values |= {"crank_angle_deg": angle, "assembly": draw(_branch)}
    return "four_bar", values | _coupler_point(draw, coupler) | _rates(draw)


@st.composite
def _slider_crank(draw: st.DrawFn) -> PresetValues:
    crank, angle = draw(_scale), draw(_angle)
    rod = crank * draw(st.floats(0.3, 5.0))
    offset = _guide_height(draw, crank * math.sin(math.radians(angle)), rod)
    values = {"crank": crank, "rod": rod, "offset": offset, "crank_angle_deg": angle}
    values["assembly"] = draw(_branch)
    return "slider_crank", values | _coupler_point(draw, rod) | _rates(draw)


def _slotted_lever(draw: st.DrawFn) -> dict[str, float]:
    """Crank, ground, slot offset and lever: the pin stays clear of the pivot over a whole turn."""
    ground = draw(_scale)
    crank = ground * draw(_ratio)
    offset = abs(ground - crank) * draw(st.floats(-0.8, 0.8))
    lever = (ground + crank) * draw(st.floats(1.05, 2.0))
    return {"crank": crank, "ground": ground, "slot_offset": offset, "lever": lever}


@st.composite
def _inverted_slider_crank(draw: st.DrawFn) -> PresetValues:
    values = _slotted_lever(draw) | {"crank_angle_deg": draw(_angle)}
    return "inverted_slider_crank", values | _rates(draw)


@st.composite
def _quick_return(draw: st.DrawFn) -> PresetValues:
    values = _slotted_lever(draw) | {"crank_angle_deg": draw(_angle)}
    # B depends on neither the rod nor the ram: read it off a pose with a rod long enough to reach
    probe = build_preset("quick_return", values | {"rod": 1e4, "ram_height": 0.0})
    rod = values["ground"] * draw(st.floats(0.2, 2.0))
    values |= {"rod": rod, "ram_height": _guide_height(draw, probe["points"]["B"][1], rod)}
    return "quick_return", values | _rates(draw)


@st.composite
def _slider_guide_extension(draw: st.DrawFn) -> PresetValues:
    crank, angle = draw(_scale), draw(_angle)
    coupler = crank * draw(st.floats(0.3, 5.0))
    height = _guide_height(draw, crank * math.sin(math.radians(angle)), coupler)
    values = {"crank": crank, "coupler": coupler, "guide_height": height, "crank_angle_deg": angle}
    values["extension"] = coupler * draw(st.floats(0.01, 2.0))
    return "slider_guide_extension", values | _rates(draw)


@st.composite
def _seed004(draw: st.DrawFn) -> PresetValues:
    """Seed 004 at any crank angle, with a rocker that keeps it a crank-rocker."""
    values = {"crank": 0.15, "coupler": 1.0, "ground": 1.0, "extension": 0.15}
    values |= {"crank_angle_deg": draw(_angle), "rocker": draw(st.floats(0.4, 0.7))}
    return "seed004", values | _rates(draw)


_BY_NAME: dict[str, Callable[[], st.SearchStrategy[PresetValues]]] = {
    "four_bar": _four_bar,
    "slider_crank": _slider_crank,
    "inverted_slider_crank": _inverted_slider_crank,
    "quick_return": _quick_return,
    "slider_guide_extension": _slider_guide_extension,
    "seed004": _seed004,
}
assert list(_BY_NAME) == list(PRESETS), "a preset has no strategy"


def assemblable_presets(names: Sequence[str] | None = None) -> st.SearchStrategy[PresetValues]:
    """``(name, values)`` pairs that assemble, well away from singular poses.

    ``names`` restricts the draw to some presets (default: all of them).
    """
    return st.one_of(*(_BY_NAME[name]() for name in (names or list(_BY_NAME))))
