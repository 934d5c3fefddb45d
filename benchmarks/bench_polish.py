"""What the 40-digit polish of a posed instant (``solver.position.polish``, issue 14) costs per
/analyze.

Run from the repository root:

    python -m benchmarks.bench_polish            # about 20 s
    python -m benchmarks.bench_polish --repeats 200

``analyze(scene)`` (every kinematic quantity) of the four-bar, slider-crank and inverted
slider-crank presets and of a triad (a Newton group), each posed with ``angle_deg`` (so the
polish runs), timed with the polish and without it (``solver.analysis.instant.polish`` replaced by
the identity, the closed-form position as before issue 14), the two alternating repeat by repeat in
the same run; p50 of the wall time (and of the process's CPU time, less sensitive to other
processes) and the ratio. It prints a markdown table and the 1-minute load average before and after
(a load above 0 means other processes competed for the cores). It measures, never fails.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:  # run as `python benchmarks/bench_polish.py`
    sys.path.insert(0, str(ROOT))

import solver.analysis.instant as analysis  # noqa: E402
from solver.model.scene import LinkageScene, parse_linkage  # noqa: E402
from solver.teaching.presets import build_preset  # noqa: E402
from tests.solver.position.test_newton import TRIAD  # noqa: E402


def posed(doc: dict[str, Any], degrees: float) -> LinkageScene:
    driver = {**doc["drivers"][0], "angle_deg": degrees}
    return parse_linkage({**doc, "drivers": [driver]})


def cases() -> dict[str, LinkageScene]:
    return {
        "four_bar at 123.4 deg": posed(build_preset("four_bar", {}), 123.4),
        "slider_crank at 77 deg": posed(build_preset("slider_crank", {}), 77.0),
        "inverted_slider_crank at 30 deg": posed(build_preset("inverted_slider_crank", {}), 30.0),
        "triad (Newton group) at 70 deg": posed(TRIAD, 70.0),
    }


def unpolished(*args: Any) -> Any:
    """The closed-form motion as it came (``motion`` is the last argument), residual 0."""
    return args[-1], 0.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=60)
    repeats = parser.parse_args().repeats
    polish = analysis.polish
    functions = vars(analysis)
    load = os.getloadavg()[0]
    rows = [
        "| pose | without polish p50, ms (CPU) | with polish p50, ms (CPU) | ratio |",
        "|---|---|---|---|",
    ]
    for name, scene in cases().items():
        times: dict[bool, list[float]] = {False: [], True: []}
        cpu: dict[bool, list[float]] = {False: [], True: []}
        analysis.analyze(scene)  # warm up (imports, caches)
        for _ in range(repeats):
            for on in (False, True):
                functions["polish"] = polish if on else unpolished
                start, start_cpu = time.perf_counter(), time.process_time()
                analysis.analyze(scene)
                times[on].append(time.perf_counter() - start)
                cpu[on].append(time.process_time() - start_cpu)
        functions["polish"] = polish
        off, on_ = (statistics.median(times[k]) * 1e3 for k in (False, True))
        cpu_off, cpu_on = (statistics.median(cpu[k]) * 1e3 for k in (False, True))
        rows.append(
            f"| {name} | {off:.2f} ({cpu_off:.2f}) | {on_:.2f} ({cpu_on:.2f}) | {on_ / off:.1f}x |"
        )
    print(f"load average (1 min): {load:.2f} before, {os.getloadavg()[0]:.2f} after; "
          f"{repeats} alternating repeats\n")  # fmt: skip
    print("\n".join(rows))


if __name__ == "__main__":
    main()
