"""A benchmark's section of docs/BENCHMARKS.md: what stands between its two markers
(``<!-- name:start -->`` and ``<!-- name:end -->``) is replaced by the new report and everything
else is kept; a missing section is appended under its heading."""

from __future__ import annotations

import os
from pathlib import Path


def markers(name: str) -> tuple[str, str]:
    return f"<!-- {name}:start -->", f"<!-- {name}:end -->"


def write_section(doc: Path, name: str, heading: str, report: str, template: str = "") -> None:
    """Put ``report`` between ``name``'s markers in ``doc`` (``template`` if the file is missing),
    written through a temporary file so that an interrupted run leaves the old text."""
    start, end = markers(name)
    text = doc.read_text() if doc.exists() else template
    if start not in text or end not in text:
        text = text.rstrip() + f"\n\n## {heading}\n\n{start}\n{end}\n"
    head, rest = text.split(start, 1)
    tail = rest.split(end, 1)[1]
    doc.parent.mkdir(parents=True, exist_ok=True)
    temporary = doc.with_suffix(doc.suffix + ".tmp")
    temporary.write_text(f"{head}{start}\n{report}\n{end}{tail}")
    os.replace(temporary, doc)
