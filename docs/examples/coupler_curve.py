"""The coupler curve of a crank-rocker and its rocker's angular velocity, with the solver as a
Python library and Plotly for the figure.

    pip install -e '.[plot]'
    python docs/examples/coupler_curve.py                  # writes coupler_curve.html
    python docs/examples/coupler_curve.py --data out.json  # the numbers only (no Plotly needed)

One call, ``solver.sweep``, turns the crank through a revolution; its result is the body of
POST /api/v1/sweep, with read-only numpy arrays sample by sample.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

import solver

# A crank-rocker (lengths in m): crank AB 0.15, coupler BC 1.0 with the coupler point P,
# rocker DC 0.55, ground AD 1.0; the crank turns at 240 rpm counter-clockwise.
SCENE: dict[str, Any] = {
    "kind": "linkage",
    "title": "crank-rocker with a coupler point",
    "points": {
        "A": [0.0, 0.0],
        "B": [0.1299038105676658, 0.075],
        "C": [1.0099380690674067, 0.5499102061093352],
        "D": [1.0, 0.0],
        "P": [0.47493889859566923, 0.48846195475461573],
    },
    "links": {
        "ground": {"points": ["A", "D"], "ground": True},
        "crank": {"points": ["A", "B"]},
        "coupler": {"points": ["B", "C", "P"]},
        "rocker": {"points": ["D", "C"]},
    },
    "joints": [
        {"type": "revolute", "point": "A", "links": ["ground", "crank"]},
        {"type": "revolute", "point": "B", "links": ["crank", "coupler"]},
        {"type": "revolute", "point": "C", "links": ["coupler", "rocker"]},
        {"type": "revolute", "point": "D", "links": ["rocker", "ground"]},
    ],
    "drivers": [{"link": "crank", "omega": 8 * math.pi, "alpha": 0.0}],
}


def curves(samples: int = 360) -> dict[str, list[float]]:
    """The coupler point's path and the rocker's omega over one revolution of the crank."""
    cycle = solver.sweep(SCENE, samples, ["position", "velocity"])
    P = cycle["points"]["P"]["position"]
    return {
        "crank_angle_deg": [math.degrees(a) for a in cycle["driver_angle"]],
        "coupler_x": P[:, 0].tolist(),
        "coupler_y": P[:, 1].tolist(),
        "omega_rocker": cycle["links"]["rocker"]["omega"].tolist(),
    }


def figure(data: dict[str, list[float]]) -> Any:
    """Two panels: the coupler curve (equal axes) and omega of the rocker against crank angle."""
    from plotly.subplots import make_subplots

    fig = make_subplots(
        rows=1, cols=2, subplot_titles=("Coupler curve of P", "Angular velocity of the rocker")
    )
    fig.add_scatter(x=data["coupler_x"], y=data["coupler_y"], name="P", row=1, col=1)
    fig.add_scatter(
        x=data["crank_angle_deg"], y=data["omega_rocker"], name="omega rocker", row=1, col=2
    )
    fig.update_xaxes(title_text="x (m)", row=1, col=1)
    fig.update_yaxes(title_text="y (m)", scaleanchor="x", scaleratio=1, row=1, col=1)
    fig.update_xaxes(title_text="crank angle (deg)", row=1, col=2)
    fig.update_yaxes(title_text="omega (rad/s)", row=1, col=2)
    return fig


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", type=Path, help="write the numbers as JSON here, no figure")
    parser.add_argument("--html", type=Path, default=Path("coupler_curve.html"))
    args = parser.parse_args()
    data = curves()
    if args.data:
        args.data.write_text(json.dumps(data))
        return
    figure(data).write_html(args.html, include_plotlyjs=True)
    print(f"wrote {args.html}")


if __name__ == "__main__":
    main()
