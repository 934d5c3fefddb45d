"""A Newton group's branch between its limit positions, and the message where it cannot close
(solver/position/continuation.py).

The triad of tests/solver/position/test_newton.py rocks between two limit positions, low < 0 < high
(turns of the crank from its drawn pose, found by the sweep). The branch reaches a turn t exactly
when low <= t <= high, either sign; the full-turning triad of benchmarks/bench_newton.py reaches
any turn. Asked to pose the rocking triad 0.5 rad beyond a limit, the solver says which loop and
which crank angle (the drawn angle atan2(0.2, 0.3) plus the turn, in degrees).
"""

from __future__ import annotations

import math
import re

import pytest

from benchmarks.bench_newton import FULL_TURN
from solver.analysis.instant import analyze
from solver.analysis.sweeps import sweep
from solver.errors import NotAssemblable
from solver.model.scene import parse_linkage
from solver.position.continuation import Continuation
from tests.solver.position.test_newton import TRIAD, with_angle

DRAWN = math.atan2(0.2, 0.3)  # the crank O-A of TRIAD as drawn


def limits() -> tuple[float, float]:
    """The rocking triad's limit positions as turns from the drawn pose."""
    result = sweep(parse_linkage(TRIAD), 36)
    assert not result.feasible
    low, high = (limit - DRAWN for limit in result.limits)
    assert low < 0.0 < high
    return low, high


def test_branch_reaches_the_turns_between_its_limits_and_no_others() -> None:
    low, high = limits()
    branch = Continuation(parse_linkage(TRIAD)).branch(())
    for turn in (0.0, 0.999 * high, 0.999 * low):
        assert branch.reaches(turn), turn
    for turn in (high + 1e-3, high + 0.5, low - 1e-3, low - 0.5):
        assert not branch.reaches(turn), turn
    full = Continuation(parse_linkage(FULL_TURN)).branch(())
    for turn in (-5.0, -1.0, 1.0, 5.0):
        assert full.reaches(turn)


@pytest.mark.parametrize("beyond", ["high", "low"])
def test_a_pose_beyond_a_limit_names_the_loop_and_the_crank_angle(beyond: str) -> None:
    low, high = limits()
    turn = high + 0.5 if beyond == "high" else low - 0.5
    degrees = math.degrees(DRAWN + turn)
    with pytest.raises(NotAssemblable) as caught:
        analyze(parse_linkage(with_angle(TRIAD, degrees)))
    message = str(caught.value)
    assert "the loop of T, L1, L2, L3 cannot be closed at crank angle" in message
    found = re.findall(r"crank angle (\S+) deg", message)
    assert found and all(float(x) == pytest.approx(degrees, abs=1e-3) for x in found)
