"""The solver as a library: ``import solver``, frozen results, unknown-key warnings.

The HTTP side of the same contract (``as_dict()`` equals the body the endpoint sends) is in
tests/server/test_contract.py; these tests need numpy, scipy and sympy only.
"""

from __future__ import annotations

import copy
import json
import math
import runpy
import subprocess
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import solver
from solver.analysis.results import Result, holds
from solver.kinematics.spatial import SpatialChain
from solver.model.scene import LinkageScene, parse_linkage, unknown_keys
from solver.teaching.presets import build_preset
from tests.solver.position.test_assembly import _near_crank_rocker

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "server" / "examples"
WEB = ("fastapi", "pydantic", "starlette", "httpx", "orjson", "uvicorn")


def example(name: str) -> dict[str, Any]:
    data: dict[str, Any] = json.loads((EXAMPLES / f"{name}.json").read_text())
    return data


def test_the_public_names() -> None:
    for name in ("parse_scene", "analyze", "sweep", "sweep_time", "find_event", "solve"):
        assert callable(getattr(solver, name)), name
    assert set(solver.__all__) <= set(dir(solver))


@pytest.mark.parametrize("name", ["S000-T1", "S002-spatial-arm"])
def test_a_dict_and_a_parsed_scene_give_the_same_result(name: str) -> None:
    doc = example(name)
    scene = solver.parse_scene(doc)
    assert isinstance(scene, LinkageScene | SpatialChain)
    assert solver.analyze(doc).as_dict() == solver.analyze(scene).as_dict()
    assert solver.solve(doc).as_dict() == solver.solve(scene).as_dict()


def test_the_numbers_are_the_solvers() -> None:
    """scene-v1's own example: omega of link 2 is 0.25 rad/s, alpha 0.09375 rad/s^2."""
    result = solver.analyze(example("S000-T1"))
    coupler = result["links"]["coupler"]
    assert coupler["omega"] == pytest.approx(0.25, abs=1e-12)
    assert coupler["alpha"] == pytest.approx(0.09375, abs=1e-12)
    assert result["points"]["C"]["velocity"] == pytest.approx((1.0, 0.5), abs=1e-12)


def test_solver_sweeps_and_solver_sweep_do_not_clash() -> None:
    """In a fresh interpreter: after ``import solver.analysis.sweeps`` and every other module of the
    package, ``solver.analysis.sweeps`` is the module and ``solver.sweep`` (every public name) is
    still the
    function it was, and it still sweeps."""
    code = "; ".join(
        [
            "import importlib, inspect, json, pkgutil",
            "import solver.analysis.sweeps",
            "from solver import sweep",
            "public = {name: getattr(solver, name) for name in solver.__all__}",
            "modules = pkgutil.walk_packages(solver.__path__, 'solver.')",
            "[importlib.import_module(module.name) for module in modules]",
            "assert all(getattr(solver, name) is public[name] for name in public)",
            "assert inspect.ismodule(solver.analysis.sweeps) and solver.sweep is sweep",
            f"doc = json.loads(open({str(EXAMPLES / 'S000-T1.json')!r}).read())",
            "assert solver.sweep(doc, 4)['samples'] == 4",
        ]
    )
    run = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr[-3000:]


def test_linkage_only_calls_refuse_a_spatial_chain() -> None:
    doc = example("S002-spatial-arm")
    with pytest.raises(solver.InvalidScene, match="takes a 'linkage' scene"):
        solver.sweep(doc, 10)
    with pytest.raises(solver.InvalidScene, match="kind: expected"):
        solver.analyze({"kind": "planar"})


def test_sweep_time_and_find_event() -> None:
    doc = example("S003-T2-rotating-carrier")
    over = solver.sweep_time(doc, (0.0, 1.0), 11, ["position", "velocity"])
    assert over["time"][0] == 0.0 and over["time"][-1] == 1.0 and over["samples"] == 11
    assert set(over["moving_points"]) == {m["name"] for m in doc["moving_points"]}
    event = solver.find_event(doc, doc["moving_points"][0]["name"], "P", 1, 60.0)
    assert event["time"] > 0.0 and len(event["position"]) == 2


# --- complete: the sweep's link angles -----------------------------------------------------------


def test_sweep_link_angles_are_the_instants() -> None:
    """A sweep's absolute link angles equal /analyze's at the same driver angle (1e-12 rad), and
    at the first sample (the drawn pose of a crank that turns fully) the atan2 of the drawn
    points."""
    doc = build_preset("four_bar", {})
    cycle = solver.sweep(doc, 12)
    assert cycle["feasible"]
    for k in (0, 5):
        at = copy.deepcopy(doc)
        at["drivers"][0]["angle_deg"] = math.degrees(float(cycle["driver_angle"][k]))
        instant = solver.analyze(at, ["position"])
        for name, link in instant["links"].items():
            assert cycle["links"][name]["angle"][k] == pytest.approx(link["angle"], abs=1e-12)
    (x0, y0), (x1, y1) = doc["points"]["D"], doc["points"]["C"]
    assert cycle["links"]["rocker"]["angle"][0] == pytest.approx(math.atan2(y1 - y0, x1 - x0))


def test_one_rule_decides_what_a_result_holds() -> None:
    only_poles = holds(frozenset({"poles"}))
    assert only_poles.omega and only_poles.alpha and not only_poles.velocity
    assert not holds(frozenset({"position"})).omega
    doc = example("S000-T1")
    for quantities in (["position"], ["velocity"], ["poles"], ["acceleration", "components"]):
        instant = solver.analyze(doc, quantities)["links"]["coupler"]
        cycle = solver.sweep(doc, 8, quantities)["links"]["coupler"]
        assert set(instant) == set(cycle), quantities


# --- immutable -----------------------------------------------------------------------------------


def test_results_cannot_be_changed() -> None:
    doc = example("S000-T1")
    instant = solver.analyze(doc)
    cycle = solver.sweep(doc, 16, ["position", "velocity"])
    with pytest.raises(TypeError):
        instant["links"]["coupler"]["omega"] = 1.0  # type: ignore[index]
    with pytest.raises(TypeError):
        instant["points"]["C"]["velocity"][0] = 1.0  # type: ignore[index]
    with pytest.raises(AttributeError):
        instant.extra = 1  # type: ignore[attr-defined]
    omega = cycle["links"]["rocker"]["omega"]
    assert not omega.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        omega[0] = 1.0


def test_changing_an_input_or_an_output_cannot_change_a_result() -> None:
    doc = example("S000-T1")
    instant, cycle = solver.analyze(doc), solver.sweep(doc, 16, ["position", "velocity"])
    before = (copy.deepcopy(instant.as_dict()), {k: np.copy(v) for k, v in _arrays(cycle)})
    doc["points"]["C"][0] = 7.0
    doc["drivers"][0]["omega"] = 100.0
    body = instant.as_dict()
    body["links"]["coupler"]["omega"] = 1e9
    body["points"]["C"]["velocity"][0] = 1e9
    cycle.as_dict()["points"]["C"].clear()
    assert instant.as_dict() == before[0]
    for key, values in _arrays(cycle):
        np.testing.assert_array_equal(values, before[1][key])


def test_a_result_keeps_a_copy_of_what_it_was_given() -> None:
    """No shared memory: the arrays handed to a result are copied before they are frozen."""
    values = np.arange(3.0)
    nested = {"a": [1.0, 2.0]}
    result = Result({"x": values, "n": nested, "warnings": []})
    values[0], nested["a"][0] = 9.0, 9.0
    assert result["x"].tolist() == [0.0, 1.0, 2.0] and result["n"]["a"] == (1.0, 2.0)
    assert not np.shares_memory(result["x"], values)


def _arrays(result: Result) -> list[tuple[str, np.ndarray]]:
    found = []
    for kind in ("points", "links"):
        for name, fields in result[kind].items():
            found += [
                (f"{kind}.{name}.{k}", v) for k, v in fields.items() if isinstance(v, np.ndarray)
            ]
    return found


# --- typos are never silent ----------------------------------------------------------------------


def test_a_typo_is_a_warning_and_strict_makes_it_an_error() -> None:
    doc = example("S000-T1")
    doc["drivers"][0]["angle"] = 120
    expected = ("drivers[0].angle is not a scene field; did you mean angle_deg?",)
    for result in (
        solver.analyze(doc),
        solver.sweep(doc, 8),
        solver.solve(doc),
    ):
        assert result.warnings == expected
    assert solver.solve(doc)["results"]["warnings"] == expected
    with pytest.warns(solver.SceneWarning, match="angle_deg"):
        solver.parse_scene(doc)
    for call in (solver.analyze, solver.solve, solver.parse_scene):
        with pytest.raises(solver.InvalidScene, match=r"drivers\[0\]\.angle"):
            call(doc, strict=True)  # type: ignore[operator]


def test_every_example_and_the_extensions_keys_are_known() -> None:
    """The spec's examples, and a scene using every dynamics-v1 field, give no warning."""
    for path in EXAMPLES.glob("*.json"):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert solver.analyze(json.loads(path.read_text()), strict=True).warnings == ()
    doc = example("S000-T1")
    doc |= {
        "masses": {
            "crank": {"mass": 30, "bar": ["A", "B"]},
            "rocker": {"mass": 60, "center": [1.0, 0.35], "inertia": 2.45},
        },
        "point_masses": [{"name": "mD", "link": "rocker", "point": "C", "mass": 90}],
        "gravity": [0, -9.81],
        "forces": [
            {
                "name": "F",
                "link": "rocker",
                "point": "C",
                "magnitude": "10",
                "direction_deg": 90,
                "relative_to": "link",
            }
        ],
        "torques": [{"name": "M", "link": "rocker", "moment": "-50"}],
    }
    assert unknown_keys(doc) == []


def test_a_read_scene_keeps_its_warnings_for_the_result() -> None:
    """read_scene: look at the scene first (a cost check), the result still reports the typo."""
    doc = example("S000-T1")
    doc["drivers"][0]["angle"] = 120
    read = solver.read_scene(doc)
    assert isinstance(read.scene, LinkageScene)
    assert read.warnings == ("drivers[0].angle is not a scene field; did you mean angle_deg?",)
    assert solver.analyze(read).warnings == read.warnings
    assert solver.sweep(read, 8).warnings == read.warnings
    with pytest.raises(solver.InvalidScene):
        solver.read_scene(doc, strict=True)


def test_the_solvers_own_warnings_follow_the_requests() -> None:
    """A result's body lists the request's warnings first, then the solver's own (a pose within
    1e-3 of the size of a change point, tests/solver/position/test_assembly.py)."""
    doc = _near_crank_rocker(1e-4, 179.0)
    doc["drivers"][0]["angle"] = 120
    found = solver.analyze(doc).warnings
    assert len(found) == 2
    assert found[0] == "drivers[0].angle is not a scene field; did you mean angle_deg?"
    assert "change point" in found[1]


def test_a_parsed_scene_carries_no_key_warnings() -> None:
    doc = example("S000-T1")
    doc["drivers"][0]["angle"] = 120
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = parse_linkage(doc)
    assert solver.analyze(scene).warnings == ()


# --- a library without the web -------------------------------------------------------------------


@pytest.mark.slow
def test_the_solver_tests_need_no_web_framework() -> None:
    """Collect tests/solver with the web packages made unimportable: nothing there needs them."""
    block = "; ".join(f"sys.modules[{name!r}] = None" for name in WEB)
    code = f"import sys; {block}; import pytest; sys.exit(pytest.main(['--collect-only', '-q', "
    code += "'-p', 'no:cacheprovider', 'tests/solver']))"
    run = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=300
    )
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]


def test_the_example_writes_its_data_without_plotly(tmp_path: Path) -> None:
    """docs/examples/coupler_curve.py --data: the coupler curve and the rocker's omega are the
    sweep's own numbers (Plotly blocked, so the data path never needs it)."""
    out = tmp_path / "curves.json"
    script = ROOT / "docs" / "examples" / "coupler_curve.py"
    code = (
        "import sys, runpy; sys.modules['plotly'] = None; "
        f"sys.argv = ['coupler_curve.py', '--data', {str(out)!r}]; "
        f"runpy.run_path({str(script)!r}, run_name='__main__')"
    )
    run = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr[-3000:]
    data = json.loads(out.read_text())
    scene = runpy.run_path(str(script), run_name="example")["SCENE"]
    cycle = solver.sweep(scene, 360, ["position", "velocity"])
    assert data["coupler_x"] == cycle["points"]["P"]["position"][:, 0].tolist()
    assert data["omega_rocker"] == cycle["links"]["rocker"]["omega"].tolist()
    # The crank-rocker's rocker swings both ways once per revolution.
    omega = np.array(data["omega_rocker"])
    assert omega.max() > 0.0 > omega.min()
