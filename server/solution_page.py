"""The printable page of a worked solution: standalone HTML from a template.

``templates/solution.html`` holds the page (its print style, and the one inline script that
typesets the steps with KaTeX from /vendor/katex/; nothing is loaded from another host). This
module fills it from the /solution body and the scene document, escaping every name.
"""

from __future__ import annotations

import html
import json
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from string import Template
from typing import Any

TEMPLATE = Template((Path(__file__).parent / "templates" / "solution.html").read_text())
METHODS = {
    "vector": "relative velocities (vector method)",
    "loop": "loop closure in complex form",
    "newton_euler": "Newton-Euler (joint forces and the driving torque)",
    "statics": "Static force analysis (joint forces and the holding torque)",
    "tabular": "the tabular (Willis) method and the formula method",
    "cam": "the follower's motion law and the cam's geometry",
}


def _e(text: object) -> str:
    return html.escape(str(text), quote=True)


def _vector(value: Any) -> str:
    if isinstance(value, list | tuple):
        return "(" + ", ".join(f"{float(x):.6g}" for x in value) + ")"
    return _e(value)


def _table(caption: str, header: Sequence[str], rows: Iterable[Sequence[str]]) -> str:
    """An HTML table: caption, a header row, and rows of cells already escaped."""
    head = "".join(f"<th>{h}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><caption>{caption}</caption><tr>{head}</tr>{body}</table>"


def _driver_motion(d: Mapping[str, Any]) -> str:
    if "angle_law" in d:
        return f"angle law {_e(d['angle_law'])} rad"
    return f"omega = {_e(d.get('omega', 0))} rad/s, alpha = {_e(d.get('alpha', 0))} rad/s^2" + (
        f", angle {_e(d['angle_deg'])} deg" if "angle_deg" in d else ""
    )


def _scene_tables(doc: Mapping[str, Any]) -> str:
    """The scene's data as tables (from the validated document)."""
    if doc.get("kind") == "spatial_chain":
        return _chain_tables(doc)
    if doc.get("kind") == "gear_train":
        return _gear_tables(doc)
    if doc.get("kind") == "cam":
        return _cam_tables(doc)
    instant = f"<p>Analysed instant: t = {_e(doc['time'])} s.</p>" if "time" in doc else ""
    return _linkage_tables(doc) + _moving_point_table(doc.get("moving_points", [])) + instant


def _chain_tables(doc: Mapping[str, Any]) -> str:
    """A spatial chain's joints and points."""
    return _table(
        "Joints (origin m, rate rad/s or m/s)",
        ["joint", "type", "origin", "axis", "rate", "rate of rate"],
        (
            [
                _e(j.get("name")),
                _e(j.get("type")),
                _vector(j.get("origin")),
                _vector(j.get("axis")),
                _e(j.get("rate")),
                _e(j.get("rate_dot", 0)),
            ]
            for j in doc.get("joints", [])
        ),
    ) + _table(
        "Points (m)",
        ["point", "body", "position"],
        (
            [_e(n), _e(p.get("body")), _vector(p.get("position"))]
            for n, p in doc.get("points", {}).items()
        ),
    )


def _gear_tables(doc: Mapping[str, Any]) -> str:
    """A gear train's gears, meshes and inputs."""
    mounts = doc.get("mounts", {})
    return (
        _table(
            "Gears",
            ["gear", "teeth", "", "axis"],
            (
                [
                    _e(n),
                    _e(g.get("teeth")),
                    "internal" if g.get("internal") else "external",
                    _e(f"on {mounts[n]}" if n in mounts else "frame"),
                ]
                for n, g in doc.get("gears", {}).items()
            ),
        )
        + _table(
            "Meshes, shafts and carriers",
            ["", "members"],
            [["mesh", _e(" - ".join(map(str, m)))] for m in doc.get("meshes", [])]
            + [["shaft", _e(", ".join(map(str, s)))] for s in doc.get("shafts", [])]
            + [["carrier", _e(c)] for c in doc.get("carriers", [])],
        )
        + _table(
            "Inputs (rad/s)",
            ["member", "omega"],
            ([_e(n), _e(w)] for n, w in doc.get("inputs", {}).items()),
        )
    )


def _cam_tables(doc: Mapping[str, Any]) -> str:
    """A cam's circle, speed, follower and segments."""
    cam, follower = doc.get("cam", {}), doc.get("follower", {})
    return _table(
        "Cam and follower (m, rad/s)",
        ["field", "value"],
        (
            [_e(k), _vector(v)]
            for k, v in (*cam.items(), *follower.items())
            if isinstance(v, str | int | float | list)
        ),
    ) + _table(
        "Segments (lift in m, or rad for an oscillating follower)",
        ["segment", "type", "law", "lift", "duration (deg)"],
        (
            [str(i), _e(s.get("type")), _e(s.get("law", "")), _e(s.get("lift", "")),
             _e(s.get("duration_deg"))]
            for i, s in enumerate(doc.get("segments", []))
        ),
    )  # fmt: skip


def _linkage_tables(doc: Mapping[str, Any]) -> str:
    """A linkage's drawn points, links, joints and drivers."""
    return (
        _table(
            "Points as drawn (m)",
            ["point", "position"],
            ([_e(n), _vector(xy)] for n, xy in doc.get("points", {}).items()),
        )
        + _table(
            "Links",
            ["link", "points", ""],
            (
                [
                    _e(n),
                    _e(", ".join(map(str, link.get("points", [])))),
                    "ground" if link.get("ground") else "",
                ]
                for n, link in doc.get("links", {}).items()
            ),
        )
        + _table(
            "Joints (slider and prismatic: links = guide, follower)",
            ["type", "point", "links", "slot axis"],
            (
                [
                    _e(j.get("type")),
                    _e(j.get("point")),
                    _e(", ".join(map(str, j.get("links", [])))),
                    _vector(j["axis"]) if "axis" in j else "",
                ]
                for j in doc.get("joints", [])
            ),
        )
        + _table(
            "Drivers",
            ["link", "motion"],
            ([_e(d.get("link")), _driver_motion(d)] for d in doc.get("drivers", [])),
        )
    )


def _moving_point_table(moving: Sequence[Mapping[str, Any]]) -> str:
    """The points moving along paths on links, if any."""
    if not moving:
        return ""
    return _table(
        "Moving points (s in m, t in s)",
        ["point", "carrier", "path", "s(t)"],
        (
            [
                _e(m.get("name")),
                _e(m.get("link")),
                _e(json.dumps(m.get("path"))),
                _e(m.get("s_law")),
            ]
            for m in moving
        ),
    )


def _inline_svg(figure: str) -> str:
    """A step's SVG (built with escaped labels) inside HTML, where no namespace is needed."""
    return figure.replace(' xmlns="http://www.w3.org/2000/svg"', "", 1)


def solution_page(doc: Mapping[str, Any], solution: Mapping[str, Any]) -> str:
    """The page of ``solution`` (a /solution body) for the scene document ``doc``."""
    kinds = {"spatial_chain": "spatial chain", "gear_train": "gear train"}
    title = doc.get("title") or kinds.get(str(doc.get("kind")), "linkage")
    # a step's equations scroll sideways where they are long: the keyboard reaches them
    kinds = {"spatial_chain": "spatial chain", "cam": "cam"}
    title = doc.get("title") or kinds.get(str(doc.get("kind")), "linkage")
    steps = "".join(
        f'<li class="step"><h3>{_e(s["title"])}</h3>'
        + (
            f'<div class="math pending" tabindex="0" role="group" aria-label="Equations of step '
            f'{i}" data-latex="{_e(s["latex"])}">{_e(s["latex"])}</div>'
            if s["latex"]
            else ""
        )
        + f'<p class="text">{_e(s["text"])}</p>'
        + (f'<figure class="figure">{_inline_svg(s["figure"])}</figure>' if s.get("figure") else "")
        + "</li>"
        for i, s in enumerate(solution["steps"], start=1)
    )
    mistakes = "".join(
        f"<li><strong>{_e(m['title'])}</strong><br>{_e(m['text'])}</li>"
        for m in solution["mistakes"]
    )
    note = ""
    if solution["method"] != solution["requested_method"]:
        note = (
            f'<p class="note">The {_e(solution["requested_method"])} method does not apply to '
            "this scene; the first step says why.</p>"
        )
    return TEMPLATE.substitute(
        title=_e(title),
        method=_e(METHODS[solution["method"]]),
        digits=solution["digits"],
        convention=_e(solution["convention"]),
        note=note,
        scene_tables=_scene_tables(doc),
        steps=steps,
        mistakes=mistakes or "<li>None listed for this scene.</li>",
    )
