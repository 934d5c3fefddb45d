"""The loop method's own pieces of a step (``solver.solutions.loop``): a vector value as a complex
number, an angle in degrees, a slider's (s + c i), a sum of terms; rendered when the step is
built, with the digits its checks settled."""

from __future__ import annotations

import math

from solver.solutions.builder import StepBuilder
from solver.solutions.format import Formatter
from solver.solutions.loop import Complex, Degrees, Offset, SumOf


def test_a_vector_is_written_as_a_complex_number() -> None:
    b = StepBuilder(Formatter(4), "test", "complex")
    both, real, imaginary, unit = (
        b.value("both", (1.5, -2.0), "m"),
        b.value("real", (1.5, 0.0), "m"),
        b.value("imaginary", (0.0, 2.0), "m"),
        b.value("unit", (-1.0, 0.0), ""),
    )
    b.line(Complex(both), "; ", Complex(real), "; ", Complex(imaginary), "; ", Complex(unit, "u"))
    assert b.build().latex == r"(1.5 - 2\,i); 1.5; 2\,i; -u"


def test_an_angle_in_degrees_a_slider_offset_and_a_sum_of_terms() -> None:
    b = StepBuilder(Formatter(4), "test", "pieces")
    angle = b.value("phi", -math.pi / 2, "rad")
    s, c, zero = b.value("s", 0.25, "m"), b.value("c", -0.1, "m"), b.value("c0", 0.0, "m")
    first, second = b.value("t1", (2.0, 0.0), "m"), b.value("t2", (-3.0, 0.0), "m")
    b.line(Degrees(angle), "; ", Offset(s, c), "; ", Offset(s, zero), "; ")
    b.line(SumOf((Complex(first), Complex(second))))
    assert b.build().latex == (
        r"\begin{aligned} (-90{}^{\circ}); (0.25 - 0.1\,i); 0.25;  \\ 2 - 3 \end{aligned}"
    )
