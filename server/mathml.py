"""LaTeX to MathML on the server, for the printable sheets (``solver.exercises.export``): a sheet
saved to disk or printed shows every formula with no script and no external file; browsers
render MathML Core natively (Chromium since 109, Firefox, Safari)."""

from __future__ import annotations

from html import escape

from latex2mathml.converter import convert


def mathml(latex: str) -> str:
    """``<math display="block">`` of one line of LaTeX, or its source in ``<code>`` when the
    converter cannot read it (a sheet never fails for one formula). ``aligned`` (the worked
    solutions' equations) is read as ``align*``, the same alignment, which the converter makes a
    table of (it reads ``aligned``'s ``&`` as a letter)."""
    latex = latex.replace(r"\begin{aligned}", r"\begin{align*}")
    latex = latex.replace(r"\end{aligned}", r"\end{align*}")
    try:
        return convert(latex, display="block")
    except Exception:
        return f"<code class='tex'>{escape(latex)}</code>"
