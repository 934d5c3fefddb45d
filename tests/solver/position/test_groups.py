"""The closed-form groups are plug-ins: every group step of a plan is answered by the module of
its Assur group (solver.position.groups), and the RRR formula lives once (``rrr.chord``)."""

from __future__ import annotations

import numpy as np
import pytest

from solver.kinematics.rigid import PointMotion, solve_2x2
from solver.model.scene import parse_linkage
from solver.position import groups
from solver.position.groups import loci, prp, rpr, rrp, rrr
from solver.position.topology import DyadStep, LeverStep, build_plan
from solver.teaching.presets import PRESETS, build_preset


def test_registry_holds_one_group_per_assur_kind() -> None:
    assert set(groups.GROUPS) == {"RRR", "RRP", "PRP", "RPR"}
    modules = {"RRR": rrr, "RRP": rrp, "PRP": prp, "RPR": rpr}
    for kind, group in groups.GROUPS.items():
        assert group.kind == kind
        assert group is modules[kind].GROUP


@pytest.mark.parametrize("preset", sorted(PRESETS))
def test_every_group_step_of_a_preset_has_its_group(preset: str) -> None:
    scene = parse_linkage(build_preset(preset, {}))
    for step in build_plan(scene).steps:
        if isinstance(step, DyadStep | LeverStep):
            assert groups.group_of(step).kind == step.kind


def test_step_kind_follows_its_loci() -> None:
    """The four-bar's dyad is on two circles (RRR); the slider-crank's on a circle and a slot
    (RRP); the quick-return's lever is RPR."""
    kinds = {}
    for preset in ("four_bar", "slider_crank", "quick_return"):
        if preset not in PRESETS:
            continue
        scene = parse_linkage(build_preset(preset, {}))
        kinds[preset] = {
            s.kind for s in build_plan(scene).steps if isinstance(s, DyadStep | LeverStep)
        }
    assert kinds["four_bar"] == {"RRR"}
    assert kinds["slider_crank"] == {"RRP"}
    if "quick_return" in kinds:
        assert "RPR" in kinds["quick_return"]


def test_rrr_chord_is_the_intersection_of_the_circles() -> None:
    """A 3-4-5 triangle: centres 5 apart, radii 4 and 3: a = 3.2, h = 2.4 (|C1X| = 4)."""
    cut = rrr.chord(np.array([[5.0, 0.0]]), 4.0, 3.0)
    assert cut.d[0] == 5.0 and cut.a[0] == pytest.approx(3.2) and cut.h2[0] == pytest.approx(5.76)
    circles = [
        loci.Circle(PointMotion(np.array([c])), r, n, "link")
        for c, r, n in (([0.0, 0.0], 4.0, "A"), ([5.0, 0.0], 3.0, "B"))
    ]
    X = groups.intersect(circles[0], circles[1], "X").point(np.array([1.0]))
    assert X[0] == pytest.approx([3.2, 2.4])


def test_the_margin_pieces_change_at_the_rate_of_the_centres_distance() -> None:
    """C1 at rest, C2 = (3 + t, 4 + 2 t): d(t) = |C2 - C1|, so the stretched piece r1 + r2 - d
    falls and the folded one d - |r1 - r2| rises at dd/dt, against a central difference (h =
    1e-6, to 1e-8) and the closed form u.(v2 - v1) = (3 + 2 * 4) / 5 = 2.2 at t = 0."""
    d_vec = np.array([[3.0, 4.0]])
    cut = rrr.chord(d_vec, 4.0, 2.0)
    stretching, folding = rrr.piece_rates(cut.u, np.zeros((1, 2)), np.array([[1.0, 2.0]]))
    assert stretching is not None and folding is not None
    h = 1e-6
    (stretched_ahead, _), (stretched_behind, _) = (
        rrr.margin_pieces(np.hypot(3.0 + s * h, 4.0 + 2.0 * s * h), 4.0, 2.0) for s in (1.0, -1.0)
    )
    assert stretching[0] == pytest.approx((stretched_ahead - stretched_behind) / (2 * h), abs=1e-8)
    assert folding[0] == pytest.approx(2.2, rel=1e-15) and stretching[0] == -folding[0]
    assert rrr.piece_rates(cut.u, None, np.array([[1.0, 2.0]])) == (None, None)


def test_coincident_centres_take_any_direction() -> None:
    cut = rrr.chord(np.array([[0.0, 0.0], [1.0, 0.0]]), 1.0, 1.0)
    assert tuple(cut.u[0]) == (1.0, 0.0) and cut.u[1, 0] == 1.0


def test_one_2x2_solve_by_cramers_rule() -> None:
    """[2 1; 1 3] x = [3; 5]: x = (4/5, 7/5), column by column and into given arrays."""
    x, y = solve_2x2((2.0, 1.0), (1.0, 3.0), (3.0, 5.0))
    assert (x, y) == pytest.approx((0.8, 1.4))
    out = (np.empty(2), np.empty(2))
    ones = np.ones(2)
    solve_2x2((2.0 * ones, ones), (ones, 3.0 * ones), (3.0 * ones, 5.0 * ones), out=out)
    assert out[0] == pytest.approx([0.8, 0.8]) and out[1] == pytest.approx([1.4, 1.4])


@pytest.mark.parametrize("preset", ["four_bar", "slider_crank", "quick_return"])
def test_group_gradients_give_the_drawn_branch(preset: str) -> None:
    """At the drawn pose a two-branch dyad's constraint gradients (``Group.gradients``: X - C
    for a circle, the slot's normal for a line) cross with the sign of its drawn branch; a lever
    gives None (``polish`` does not check its branch), and so does a pin in two slots."""
    scene = parse_linkage(build_preset(preset, {}))
    for step in build_plan(scene).steps:
        if not isinstance(step, DyadStep | LeverStep):
            continue
        g = groups.group_of(step).gradients(
            step, lambda link, point: scene.drawn(point), lambda link: (1.0, 0.0)
        )
        if isinstance(step, LeverStep) or step.kind == "PRP":
            assert g is None
            continue
        assert g is not None
        g1, g2 = (np.asarray(v, dtype=float) for v in g)
        cross = g1[0] * g2[1] - g1[1] * g2[0]
        assert np.sign(cross) == step.sign
