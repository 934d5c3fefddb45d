"""The golden corpus: every public answer the server gives for the bundled examples and presets.

A refactoring that must not change behaviour records the corpus before and after and compares
the two byte for byte::

    python -m tests.golden_corpus record /tmp/golden-before
    ... change the code ...
    python -m tests.golden_corpus record /tmp/golden-after
    diff -r /tmp/golden-before /tmp/golden-after

Each file holds one request's status line, content type and body, exactly as the server sent
them. It covers /analyze, /sweep (by angle and in time), /events, /solution and solution.html in
every method, /presets, /balance and every exercise type at every difficulty, with its worked
solution, a check of its key and a wrong answer, and every export format. Not a test: a tool
for changes that promise the same answers.
"""

from __future__ import annotations

import hashlib
import json
import sys
from pathlib import Path
from typing import Any

from fastapi.testclient import TestClient

from server.app import app

API = "/api/v1"
EXAMPLES = Path(__file__).resolve().parents[1] / "server" / "examples"
METHODS = ("vector", "loop", "newton_euler")
FORMATS = ("moodle_xml", "html", "csv", "json")


def _write(out: Path, name: str, response: Any) -> None:
    head = f"{response.status_code} {response.headers.get('content-type', '')}\n"
    (out / name).write_bytes(head.encode() + response.content)


def _scenes(client: TestClient) -> dict[str, dict[str, Any]]:
    scenes = {p.stem: json.loads(p.read_text()) for p in sorted(EXAMPLES.glob("*.json"))}
    presets = client.get(f"{API}/presets").json()["presets"]
    for preset in presets:
        answer = client.post(f"{API}/presets/{preset['name']}", json={})
        if answer.status_code == 200:
            scenes[f"preset-{preset['name']}"] = answer.json()
    return scenes


def record(out: Path) -> int:
    out.mkdir(parents=True, exist_ok=True)
    count = 0
    with TestClient(app, raise_server_exceptions=False) as client:

        def post(name: str, path: str, body: dict[str, Any]) -> Any:
            nonlocal count
            response = client.post(f"{API}{path}", json=body)
            _write(out, name, response)
            count += 1
            return response

        # The first request of a worker pays for its start (imports, compilation): under load
        # that can pass the 2 s limit of /analyze, so one unrecorded request comes first.
        scenes = _scenes(client)
        client.post(f"{API}/analyze", json={"scene": scenes["S000-T1"]})
        presets = client.get(f"{API}/presets")
        _write(out, "presets.txt", presets)
        for preset in presets.json()["presets"]:
            post(f"preset-{preset['name']}.txt", f"/presets/{preset['name']}", {})
        for name, scene in scenes.items():
            dynamic = ["forces", "energy"] if "masses" in json.dumps(scene) else []
            post(f"{name}.analyze.txt", "/analyze", {"scene": scene})
            post(
                f"{name}.analyze-all.txt",
                "/analyze",
                {
                    "scene": scene,
                    "quantities": [
                        "position",
                        "velocity",
                        "acceleration",
                        "poles",
                        "components",
                        *dynamic,
                    ],
                },
            )
            for samples in (36, 361):
                post(
                    f"{name}.sweep{samples}.txt",
                    "/sweep",
                    {
                        "scene": scene,
                        "samples": samples,
                        "quantities": [
                            "position",
                            "velocity",
                            "acceleration",
                            "poles",
                            "components",
                            *dynamic,
                        ],
                    },
                )
            post(f"{name}.sweep-pos.txt", "/sweep", {"scene": scene, "samples": 90})
            post(
                f"{name}.sweep-time.txt",
                "/sweep",
                {"scene": scene, "samples": 40, "time_range": [0.0, 1.5]},
            )
            for point in [m["name"] for m in scene.get("moving_points") or []]:
                for target in scene.get("points", {}):
                    post(
                        f"{name}.events-{point}-{target}.txt",
                        "/events",
                        {"scene": scene, "event": {"moving_point": point, "reaches": target}},
                    )
            for method in METHODS:
                for digits in (4, 6):
                    post(
                        f"{name}.solution-{method}-{digits}.txt",
                        "/solution",
                        {"scene": scene, "method": method, "digits": digits},
                    )
                response = client.post(
                    f"{API}/solution.html", json={"scene": scene, "method": method}
                )
                _write(out, f"{name}.solution-{method}.html.txt", response)
            if dynamic:
                post(
                    f"{name}.balance.txt",
                    "/balance",
                    {"scene": scene, "counterweights": []},
                )
        types = client.get(f"{API}/exercises/types")
        _write(out, "exercise-types.txt", types)
        for kind in types.json()["types"]:
            for difficulty in kind["difficulties"]:
                for seed in (0, 7):
                    stem = f"exercise-{kind['name']}-{difficulty}-{seed}"
                    made = post(
                        f"{stem}.txt",
                        "/exercises",
                        {
                            "type": kind["name"],
                            "difficulty": difficulty,
                            "seed": seed,
                            "count": 2,
                            "with_solutions": True,
                        },
                    )
                    for exercise in made.json().get("exercises", []):
                        one = client.get(f"{API}/exercises/{exercise['id']}")
                        _write(out, f"{stem}.{exercise['index']}.get.txt", one)
                        key = dict(exercise.get("answers", {}))
                        for label, answers in (
                            ("right", key),
                            ("wrong", {k: -2.0 * v for k, v in key.items()}),
                        ):
                            post(
                                f"{stem}.{exercise['index']}.check-{label}.txt",
                                "/exercises/check",
                                {"id": exercise["id"], "answers": answers},
                            )
                    for fmt in FORMATS:
                        post(
                            f"{stem}.export-{fmt}.txt",
                            "/exercises/export",
                            {
                                "type": kind["name"],
                                "difficulty": difficulty,
                                "seed": seed,
                                "count": 2,
                                "with_solutions": True,
                                "format": fmt,
                            },
                        )
    digest = hashlib.sha256()
    for path in sorted(out.iterdir()):
        digest.update(path.name.encode() + path.read_bytes())
    print(f"{count + 2} answers in {out}; sha256 {digest.hexdigest()}")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] != "record":
        sys.exit("usage: python -m tests.golden_corpus record DIR")
    sys.exit(record(Path(sys.argv[2])))
