"""The dynamics panel in the browser (dynamics-v1): shown for scenes with masses, plots of the
driving torque and its mean, power, joint forces, kinetic energy and equivalent inertia over the
cycle, the frame force's hodograph with the balanced four-bar's beside it, joint-force arrows on
the animated linkage, and the Newton-Euler worked solution with its free-body diagrams."""

from __future__ import annotations

import csv
import io
import json
import math
import re
from pathlib import Path

import pytest

from solver.teaching.presets import build_preset
from tests.browser.conftest import AppPage, overlapping_pairs, shown_boxes
from tests.browser.test_app import choose, pause_and_wait, plot_data, wait_until

pytestmark = pytest.mark.browser

FRAME_FORCE = "frame force (tip of F over the cycle)"


@pytest.mark.moving
def test_seed004_shows_forces_energy_and_the_balanced_frame_force(app: AppPage) -> None:
    app.open()
    page = app.page
    assert page.locator("#dynamics").is_hidden(), "the default four-bar has no masses"
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    wait_until(lambda: plot_data(page, "dynamics-plots") != "[]", what="the dynamics plots")
    traces = json.loads(plot_data(page, "dynamics-plots"))
    names = [t["name"] for t in traces]
    assert names[:3] == ["torque M (crank)", "mean torque", "power M ω"]
    assert {"|F| at O", "|F| at A", "|F| at B", "|F| at Γ"} <= set(names)
    mean = traces[1]["y"][0]
    # seed004-dynamics.json "mean_driving_torque"; 1e-3: 241 samples of a kinked load law
    assert mean == pytest.approx(-63.6456581982242, rel=1e-3)
    assert "mean power -1600 W" in page.inner_text("#dynamics-info") or "-1599" in page.inner_text(
        "#dynamics-info"
    )
    page.check("#dynamics-balance")
    wait_until(
        lambda: (
            "balanced" in {t["name"] for t in json.loads(plot_data(page, "dynamics-hodograph"))}
        ),
        what="the balanced frame force",
    )
    curves = {t["name"]: t for t in json.loads(plot_data(page, "dynamics-hodograph"))}
    unbalanced, balanced = curves[FRAME_FORCE], curves["balanced"]

    def spread(trace: dict[str, list[float]]) -> float:
        return math.hypot(max(trace["x"]) - min(trace["x"]), max(trace["y"]) - min(trace["y"]))

    assert spread(balanced) < 0.25 * spread(unbalanced)
    # the balanced mechanism beside it, moving with the animation
    page.wait_for_selector(
        "#dynamics-balanced:not([hidden]) #balanced-linkage .link", state="attached"
    )
    drawn = page.inner_html("#balanced-linkage")
    wait_until(
        lambda: page.inner_html("#balanced-linkage") != drawn, what="the balanced mechanism to move"
    )
    app.screenshot("dynamics-seed004", "#dynamics")
    # joint forces as arrows on the animated linkage, following the frames
    page.check("#dynamics-arrows")
    page.wait_for_selector("#linkage .force-arrow", state="attached")
    assert page.locator("#linkage .force-arrow").count() == 4
    first = page.get_attribute("#linkage .force-arrow >> nth=0", "x2")
    wait_until(
        lambda: page.get_attribute("#linkage .force-arrow >> nth=0", "x2") != first,
        what="the force arrows to move with the animation",
    )
    page.uncheck("#dynamics-arrows")
    wait_until(
        lambda: page.get_attribute("#linkage g.layer-forces", "visibility") == "hidden",
        what="the arrows to hide",
    )
    app.screenshot("linkage-with-forces", "#linkage")


@pytest.mark.slow
def test_newton_euler_solution_draws_free_body_diagrams(app: AppPage) -> None:
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    pause_and_wait(page)
    page.click("#tab-solution")  # the worked solution has its own tab
    page.check("input[name='method'][value='newton_euler']")
    # The vector method's figures are there already: wait for the Newton-Euler steps themselves.
    page.wait_for_selector("#steps li:has-text('Free-body diagram of') .step-figure svg")
    page.wait_for_selector("#steps[data-typeset='done']")  # every step, not only the first ones
    free_body = page.locator("#steps li").filter(has_text="Free-body diagram of")
    assert free_body.count() == 3, "one free-body diagram per moving link"
    assert free_body.locator(".step-figure svg").count() == 3
    assert page.locator("#steps .step-error").count() == 0, "a step's LaTeX did not render"
    assert "power balance" in (page.text_content("#steps") or "")  # steps out of sight too
    app.screenshot("newton-euler-solution", ".solution-panel")


def _polar(page: object) -> dict[str, object]:
    """The polar diagram's title, its annotations (the current vector) and the pixels per newton
    of its two axes, as Plotly laid them out."""
    data: dict[str, object] = page.evaluate(  # type: ignore[attr-defined]
        """(id) => { const div = document.getElementById(id); const L = div._fullLayout;
                     const scale = (a) => a._length / (a.range[1] - a.range[0]);
                     return {title: L.title.text, arrows: div.layout.annotations.map(
                               (a) => [a.x, a.y, a.ax, a.ay, a.axref, a.ayref, a.showarrow]),
                             px: [scale(L.xaxis), scale(L.yaxis)]}; }""",
        "dynamics-hodograph",
    )
    return data


@pytest.mark.moving
def test_the_frame_force_is_a_polar_diagram(app: AppPage) -> None:
    """Seed 004's frame force drawn as textbooks draw it: the tip of F over the cycle from the
    marked origin O (the same vectors as /sweep gives), equal scales, magnitude circles labelled in
    N reaching past the largest force, spokes every 30 degrees labelled, a title, and the current
    instant's vector as an arrow from O that follows the animation."""
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    wait_until(lambda: plot_data(page, "dynamics-hodograph") != "[]", what="the polar diagram")
    traces = {t["name"]: t for t in json.loads(plot_data(page, "dynamics-hodograph"))}
    assert {"magnitude circles", "angle spokes", "magnitude labels", "angle labels"} <= set(traces)
    assert traces["origin O"]["x"] == [0] and traces["origin O"]["y"] == [0]
    status, sweep = app.post(
        "/sweep", {"scene": build_preset("seed004", {}), "samples": 241, "quantities": ["forces"]}
    )
    assert status == 200
    curve = traces[FRAME_FORCE]
    expected = sweep["frame_force"]
    assert curve["x"] == pytest.approx([f[0] for f in expected], rel=1e-12, abs=1e-9)
    assert curve["y"] == pytest.approx([f[1] for f in expected], rel=1e-12, abs=1e-9)
    largest = max(math.hypot(*f) for f in expected)
    radii = [float(label.removesuffix(" N")) for label in traces["magnitude labels"]["text"]]
    step = radii[0]
    assert radii == pytest.approx([step * (i + 1) for i in range(len(radii))], rel=1e-9)
    assert radii[-1] >= largest > radii[-1] - step, "the outer circle just encloses the curve"
    assert 1 <= len(radii) <= 6
    assert traces["angle labels"]["text"] == [f"{a}°" for a in range(0, 360, 30)]
    polar = _polar(page)
    assert "Polar diagram of the frame force" in str(polar["title"])
    px, py = polar["px"]  # type: ignore[misc]
    assert px == pytest.approx(py, rel=1e-6), "equal scales: a circle is drawn round"
    ((x, y, ax, ay, axref, ayref, shown),) = polar["arrows"]  # type: ignore[misc]
    assert (ax, ay, axref, ayref, shown) == (0, 0, "x", "y", True), "the arrow starts at O"
    assert any(
        x == pytest.approx(f[0], rel=1e-12) and y == pytest.approx(f[1], rel=1e-12)
        for f in expected
    ), "the arrow ends at the frame force of a sample"
    wait_until(
        lambda: _polar(page)["arrows"][0][:2] != [x, y],  # type: ignore[index]
        what="the current vector to follow the animation",
    )
    app.screenshot("frame-force-polar-diagram", "#dynamics-hodograph")


def test_statics_and_friction_toggle(app: AppPage) -> None:
    """The panel's statics toggle and friction coefficients ask the sweep again: in statics the
    torque is seed 004's holding torque (its mean over a turn the dynamic one's, each pose's
    different), and with mu at the pins the plot adds the torque without friction and the info
    its efficiency or why there is none."""
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics[data-asked='dynamics']")
    dynamic = json.loads(plot_data(page, "dynamics-plots"))[0]["y"]
    page.check("#dynamics-statics")
    page.wait_for_selector("#dynamics[data-asked='statics']")
    traces = json.loads(plot_data(page, "dynamics-plots"))
    static = traces[0]["y"]
    # over a revolution the kinetic and potential energies come back: the mean holding torque is
    # the mean driving torque, -W_load / 2 pi (seed004-dynamics.json "mean_driving_torque"),
    # while at each pose they differ by the inertia
    assert traces[1]["name"] == "mean torque"
    assert traces[1]["y"][0] == pytest.approx(-63.6456581982242, rel=1e-3)
    assert max(abs(a - b) for a, b in zip(static, dynamic, strict=True)) > 100
    page.fill("#dynamics-mu-pin", "0.2")
    page.dispatch_event("#dynamics-mu-pin", "change")
    page.wait_for_selector("#dynamics[data-asked='statics+friction']")
    names = [t["name"] for t in json.loads(plot_data(page, "dynamics-plots"))]
    assert "torque without friction" in names
    assert "With friction:" in page.inner_text("#dynamics-info")
    app.screenshot("dynamics-statics-friction")


@pytest.mark.slow
@pytest.mark.parametrize(("width", "height"), [(1440, 900), (1024, 768), (390, 844)])
def test_the_panel_with_statics_and_friction_fits_every_viewport(
    app: AppPage, width: int, height: int
) -> None:
    """The dynamics panel with its statics and friction fields: every field and figure inside
    the panel, no figure's title cut at its edges, the cycle plots' legend clear of their x
    axis' title, nothing scrolling sideways, axe-core clean (screenshots dynamics-panel-*)."""
    app.page.set_viewport_size({"width": width, "height": height})
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics[data-asked='dynamics']")
    page.check("#dynamics-statics")
    page.fill("#dynamics-mu-pin", "0.2")
    page.dispatch_event("#dynamics-mu-pin", "change")
    page.wait_for_selector("#dynamics[data-asked='statics+friction']")
    page.wait_for_function("() => document.querySelector('#dynamics-hodograph .gtitle') !== null")
    panel = shown_boxes(page, "#dynamics")[0]
    for box in shown_boxes(page, "#dynamics input, #dynamics button, #dynamics .js-plotly-plot"):
        assert panel[0] - 1 <= box[0] and box[2] <= panel[2] + 1, (box, panel)
    for figure in ("#dynamics-plots", "#dynamics-hodograph"):
        frame = shown_boxes(page, f"{figure} .main-svg")[0]
        for title in shown_boxes(page, f"{figure} .gtitle"):
            assert frame[0] - 1 <= title[0] and title[2] <= frame[2] + 1, (figure, title, frame)
    legend = shown_boxes(page, "#dynamics-plots .legend")
    assert not overlapping_pairs(legend + shown_boxes(page, "#dynamics-plots .xtitle"))
    assert page.evaluate("document.documentElement.scrollWidth - window.innerWidth") <= 0
    # Plotly's toolbar, shown while the pointer is over a figure, sits above the cycle plots'
    # axes (it lay on the torque curve) and clear of the polar diagram's title.
    for figure, under in (("#dynamics-plots", ".nsewdrag"), ("#dynamics-hodograph", ".gtitle")):
        page.hover(figure)
        page.wait_for_selector(f"{figure} .modebar")
        toolbar = shown_boxes(page, f"{figure} .modebar")
        covered = shown_boxes(page, f"{figure} {under}")
        assert toolbar and covered and not overlapping_pairs(toolbar + covered), (figure, toolbar)
    page.evaluate("() => document.getElementById('dynamics').scrollIntoView()")
    app.screenshot(f"dynamics-panel-{width}x{height}", "#dynamics")
    assert app.serious_accessibility_violations("#dynamics") == []


@pytest.mark.slow
def test_statics_is_a_method_of_the_worked_solution(app: AppPage) -> None:
    """The method selector offers the static force analysis: its equilibrium equations for each
    moving link, no inertia terms, and the choice kept in the shared link."""
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    pause_and_wait(page)
    page.click("#tab-solution")
    page.check("input[name='method'][value='statics']")
    page.wait_for_selector("#steps li:has-text('Equilibrium equations of')")
    page.wait_for_selector("#steps[data-typeset='done']")  # every step, not only the first ones
    equilibrium = page.locator("#steps li").filter(has_text="Equilibrium equations of")
    assert equilibrium.count() == 3, "one set of equilibrium equations per moving link"
    assert page.locator("#steps .step-error").count() == 0, "a step's LaTeX did not render"
    assert "m a_G" not in page.inner_text("#steps li:has-text('Equilibrium equations of')")
    assert app.serious_accessibility_violations(".solution-panel", formula_glyphs=False) == []
    for width, height in ((1440, 900), (1024, 768), (390, 844)):  # the selector's four choices
        page.set_viewport_size({"width": width, "height": height})
        app.screenshot(f"statics-method-{width}", ".solution-panel .panel-head")
    fragment = page.url.split("/", 3)[3]
    app.open(fragment)
    page.click("#tab-solution")
    assert page.is_checked("input[name='method'][value='statics']"), "the shared link keeps it"


def test_the_flywheel_inertia_for_k_and_the_cycle_as_csv(app: AppPage) -> None:
    """seed004: the panel gives the flywheel inertia I = ΔE / (k ω²) for the k typed (ω the
    crank's 25.13 rad/s, ΔE the energy fluctuation it prints; halving k doubles I), and
    "Download the cycle (CSV)" writes the plotted series, unrounded: one row per sample, the
    torque, the power M ω, every joint force with |F| = hypot(F_x, F_y)."""
    app.open()
    page = app.page
    choose(app, "preset:seed004")
    page.wait_for_selector("#dynamics:not([hidden])")
    omega = build_preset("seed004", {})["drivers"][0]["omega"]

    def figures() -> dict[str, float]:
        page.wait_for_function(
            "() => /flywheel inertia/.test(document.getElementById('dynamics-info').textContent)"
        )
        text = page.inner_text("#dynamics-info")
        number = r"(-?\d+(?:\.\d+)?(?:e-?\d+)?)"
        found = {
            "dE": re.search(rf"energy fluctuation {number} J", text),
            "I": re.search(rf"flywheel inertia {number} kg m² for k = {number}", text),
            "M": re.search(rf"mean torque {number} N m", text),
        }
        assert all(found.values()), text
        return {
            "dE": float(found["dE"][1]),  # type: ignore[index]
            "I": float(found["I"][1]),  # type: ignore[index]
            "k": float(found["I"][2]),  # type: ignore[index]
            "M": float(found["M"][1]),  # type: ignore[index]
        }

    first = figures()
    assert first["k"] == 0.05
    # 4 significant digits printed for both I and ΔE: 1e-3 relative
    assert first["I"] == pytest.approx(first["dE"] / (0.05 * omega**2), rel=1e-3)
    page.fill("#dynamics-k", "0.025")
    page.dispatch_event("#dynamics-k", "change")
    page.wait_for_function(
        "() => /k = 0.025/.test(document.getElementById('dynamics-info').textContent)"
    )
    second = figures()
    assert second["I"] == pytest.approx(2 * first["I"], rel=1e-3)

    with page.expect_download() as info:
        page.click("#dynamics-csv")
    assert info.value.suggested_filename == "cycle-dynamics.csv"
    rows = list(csv.reader(io.StringIO(Path(info.value.path()).read_text())))
    header, body = rows[0], [[float(v) for v in r] for r in rows[1:]]
    assert header[:3] == ["driver angle [rad]", "torque M (crank) [N m]", "power M ω [W]"]
    assert header[-2:] == ["kinetic energy T [J]", "equivalent inertia [kg m²]"]
    assert len(body) >= 100
    for row in body:
        assert row[2] == pytest.approx(row[1] * omega, rel=1e-9, abs=1e-9)
    joints = [h.removeprefix("|F| at ").removesuffix(" [N]") for h in header if h.startswith("|F|")]
    assert {"O", "A", "B"} <= set(joints)
    for name in joints:
        fx, fy, size = (header.index(f"{c} at {name} [N]") for c in ("F_x", "F_y", "|F|"))
        for row in body:
            assert row[size] == pytest.approx(math.hypot(row[fx], row[fy]), rel=1e-9, abs=1e-9)
    # the columns are the plotted series, unrounded
    traces = {t["name"]: t for t in json.loads(plot_data(page, "dynamics-plots"))}
    assert [row[1] for row in body] == pytest.approx(traces["torque M (crank)"]["y"], rel=1e-12)
    assert [row[2] for row in body] == pytest.approx(traces["power M ω"]["y"], rel=1e-12)
    size = header.index("|F| at A [N]")
    assert [row[size] for row in body] == pytest.approx(traces["|F| at A"]["y"], rel=1e-12)
