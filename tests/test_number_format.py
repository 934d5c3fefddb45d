"""The app's one rounding rule (static/js/units.js: fmt, typed, show), run under node as the page
runs it (tests/number_format_check.mjs), against Python's own formatting as the independent value.
"""

from __future__ import annotations

import json
import random
import re
import shutil
import subprocess
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]
CHECK = ROOT / "tests" / "number_format_check.mjs"
NODE = shutil.which("node")

pytestmark = pytest.mark.skipif(NODE is None, reason="node is not installed")

# Float noise as it would be printed: a run of 4+ nines or of 4+ zeros before a last digit in a
# fraction (0.289999, 0.30000000000000004), or a tiny exponent (1e-17, -3.70e-41).
NOISE = re.compile(r"\.\d*(9{4,}|0{4,}[1-9])|\de-\d{2,}")


def call(calls: list[tuple[str, list[Any]]]) -> list[Any]:
    """The results of units.js's functions for `calls` ([name, args] each), in one node process."""
    assert NODE is not None
    done = subprocess.run(
        [NODE, str(CHECK)],
        input=json.dumps(calls),
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    )
    results: list[Any] = json.loads(done.stdout)
    return results


def test_fmt_rounds_to_the_significant_digits_python_prints() -> None:
    """For 2000 random values over 1e-3..1e6 and 3..6 digits, Number(fmt(x, d)) equals Python's
    float(f"{x:.{d}g}") (to 1e-12 relative: the value above 10^d is a product of two floats)."""
    rng = random.Random(30)
    values = [
        (rng.choice((-1, 1)) * 10 ** rng.uniform(-3, 6), rng.randint(3, 6)) for _ in range(2000)
    ]
    shown = call([("fmt", [x, d]) for x, d in values])
    for (x, d), text in zip(values, shown, strict=True):
        assert float(text) == pytest.approx(float(f"{x:.{d}g}"), rel=1e-12, abs=0), (x, d, text)
        assert not NOISE.search(text), (x, d, text)
        digits = text.lstrip("-").replace(".", "").strip("0")
        assert len(digits) <= d, (x, d, text)


@pytest.mark.parametrize(
    ("name", "args", "expected"),
    [
        ("fmt", [0.28999999999999998], "0.29"),
        ("fmt", [0.1 + 0.2], "0.3"),
        ("fmt", [0.29 - 1e-17], "0.29"),
        ("fmt", [0.2900], "0.29"),
        ("fmt", [-3.7e-41, 4, 2.09], "0"),
        ("fmt", [1e-17, 4, 1.0], "0"),
        ("fmt", [-1e-13, 4, 1.0], "0"),
        ("fmt", [1.5e-7], "1.5e-7"),
        ("fmt", [2.5e7, 3], "2.5e7"),
        ("fmt", [123456.7], "123500"),
        ("fmt", [None], "—"),
        ("typed", [0.1 + 0.2], "0.3"),
        ("typed", [0.28999999999999998], "0.29"),
        ("typed", [0.15], "0.15"),
        ("typed", [0.023561944901923448], "0.0235619449019234"),
        ("show", ["length", 0.29, "mm"], "290 mm"),
        ("show", ["length", -3.7e-41, "si", 4, 2.09], "0 m"),
        ("show", ["angle", 3.141592653589793, "mm"], "180 deg"),
    ],
)
def test_a_number_is_printed_as_a_textbook_prints_it(
    name: str, args: list[Any], expected: str
) -> None:
    assert call([(name, args)]) == [expected]


def test_typed_gives_back_every_digit_a_user_typed() -> None:
    """A value typed with up to 12 significant digits (15 are kept), after a round trip through
    SI (mm -> m -> mm, deg -> rad -> deg), is shown in exactly the digits typed."""
    rng = random.Random(12)
    typed = [f"{rng.randint(1, 10**k - 1) / 10 ** rng.randint(0, k)}" for k in range(1, 12)]
    typed = [f"{float(t):.12g}" for t in typed]
    round_trips = [float(t) / 1000 * 1000 for t in typed]
    round_trips += [float(t) * (3.141592653589793 / 180) * (180 / 3.141592653589793) for t in typed]
    shown = call([("typed", [v]) for v in round_trips])
    for t, text in zip(typed * 2, shown, strict=True):
        assert float(text) == float(t), (t, text)
        assert len(text) <= len(t) + 1, (t, text)
