"""A Newton group's sweep does not depend on how finely its path is refined (issue 8: mutation
testing found the path's refinement, ``Branch.refine``, reached by no test).

A sample's starting value is interpolated on the followed path; when its first Newton step is
longer than ``continuation.BRANCH_GAP`` of the size, the path segment holding it is split and the
sample solved again. With the default gap (1e-2) the interpolation is so good that no case we
know of splits a segment, so these tests lower the gap to 1e-8, which splits segments around
most samples several times over. The answer must not change: the same feasibility and limits, the
same pose at every sample (to 1e-12 m, rounding of the final Newton-Raphson polish), on the
rocking triad (two limit positions) and the fully turning one, at 36 and 37 samples.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from benchmarks.bench_newton import FULL_TURN
from solver import continuation
from solver.scene import parse_linkage
from solver.sweeps import Sweep, sweep
from tests.solver.test_newton import TRIAD


def _sweep(doc: dict[str, Any], samples: int) -> Sweep:
    return sweep(parse_linkage(doc), samples, ["position", "velocity"])


@pytest.mark.parametrize("samples", [36, 37])
@pytest.mark.parametrize("name", ["rocking triad", "full-turn triad"])
def test_a_finely_refined_path_gives_the_same_sweep(
    name: str, samples: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    doc = TRIAD if name == "rocking triad" else FULL_TURN
    coarse = _sweep(doc, samples)
    monkeypatch.setattr(continuation, "BRANCH_GAP", 1e-8)
    fine = _sweep(doc, samples)
    assert fine.feasible == coarse.feasible == (name == "full-turn triad")
    np.testing.assert_allclose(fine.limits, coarse.limits, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(fine.driver_angle, coarse.driver_angle)
    assert fine.singular_samples.size == coarse.singular_samples.size == 0
    for point, motion in coarse.motion.points.items():
        refined = fine.motion.points[point]
        np.testing.assert_allclose(refined.p, motion.p, rtol=0, atol=1e-12)
        assert motion.v is not None and refined.v is not None
        np.testing.assert_allclose(refined.v, motion.v, rtol=0, atol=1e-9 * np.abs(motion.v).max())
