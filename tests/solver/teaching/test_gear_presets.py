"""The gear-train presets (issue 25): each builds a scene the solver accepts whose answer is the
textbook's formula for that train, to rounding (REL), and refuses teeth it cannot have."""

from __future__ import annotations

from fractions import Fraction

import pytest

import solver
from solver.teaching.gear_presets import GEAR_PRESETS, build_gear_preset
from solver.teaching.presets import PRESETS

REL = 1e-12


def members(name: str, **values: float) -> dict:
    return dict(solver.analyze(build_gear_preset(name, values))["members"])


def test_the_four_trains_of_the_issue() -> None:
    assert list(GEAR_PRESETS) == [
        "compound_reverted",
        "planetary_ring_fixed",
        "differential",
        "two_stage_planetary",
    ]
    assert not set(GEAR_PRESETS) & set(PRESETS)  # one namespace under /presets/{name}


def test_compound_reverted_value_is_the_product_of_tooth_ratios() -> None:
    """e = (N2/N3)(N4/N5) = (20/40)(16/44) = 2/11 at the defaults."""
    m = members("compound_reverted")
    assert m["gear5"]["train_value"] == pytest.approx(float(Fraction(2, 11)), rel=REL)
    m = members("compound_reverted", N2=18, N3=54, N4=24, N5=48, omega_in=-90.0)
    assert m["gear5"]["omega"] == pytest.approx(-90.0 * 18 / 54 * 24 / 48, rel=REL)


@pytest.mark.parametrize(("sun", "planet"), [(20, 30), (24, 12), (9, 40)])
def test_planetary_ring_fixed(sun: int, planet: int) -> None:
    """omega_arm / omega_sun = N_s / (N_s + N_r), N_r = N_s + 2 N_p."""
    m = members("planetary_ring_fixed", N_sun=sun, N_planet=planet, omega_sun=50.0)
    assert m["arm"]["omega"] == pytest.approx(50.0 * sun / (2 * sun + 2 * planet), rel=REL)
    assert m["ring"]["omega"] == 0.0


def test_differential_carrier_is_the_mean() -> None:
    m = members("differential", omega_left=30.0, omega_right=-12.0, N_side=31, N_planet=9)
    assert m["carrier"]["omega"] == pytest.approx(9.0, rel=REL)


def test_two_stage_planetary_is_the_product_of_the_stages() -> None:
    """(20/100)(18/90) = 1/25 at the defaults."""
    m = members("two_stage_planetary")
    assert m["arm2"]["train_value"] == pytest.approx(1 / 25, rel=REL)
    assert m["arm1"]["omega"] == m["sun2"]["omega"]


def test_refusals_with_the_numbers() -> None:
    with pytest.raises(solver.InvalidScene, match=r"20 \+ 40 = 60 but 16 \+ 40 = 56"):
        build_gear_preset("compound_reverted", {"N5": 40})
    with pytest.raises(solver.InvalidScene, match="whole number of teeth"):
        build_gear_preset("differential", {"N_side": 20.5})
    with pytest.raises(solver.InvalidScene, match=r"N_sun = 4 teeth is outside the range"):
        build_gear_preset("planetary_ring_fixed", {"N_sun": 4})
    with pytest.raises(solver.InvalidScene, match="unknown parameter"):
        build_gear_preset("differential", {"N_ring": 40})
    with pytest.raises(solver.InvalidScene, match="unknown gear preset 'watt'"):
        build_gear_preset("watt", {})
