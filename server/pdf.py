"""The exercise sheets as PDF: the self-contained HTML sheet (``solver.exercises.export``, its
formulas MathML, its figures inline SVG) printed by headless Chromium on the server.

Why Chromium: the sheet is already typeset for print (one exercise a page, ``break-after:
page``) and Chromium renders MathML Core and SVG natively, so its print is the sheet a user
prints from the browser, formula for formula. A pure-Python PDF library cannot typeset the math
(MathML) and one that renders HTML (WeasyPrint) needs Pango and its system libraries and still no
MathML. Chromium is a system package (Debian's ``chromium``, in the Dockerfile): without it a PDF
export is refused with 503 ``pdf_unavailable``, every other format still served.

The browser is ``KINEMATICS_CHROMIUM`` (a path or a command name) or the first of ``chromium``,
``chromium-browser``, ``google-chrome`` on PATH. It runs in the exercise worker, on a temporary
directory (the sheet, the PDF, its own profile), in a process group of its own that is killed
after ``timeout`` seconds.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import tempfile
from pathlib import Path

from server.problems import Unavailable
from solver.errors import LimitExceeded

BROWSER_VARIABLE = "KINEMATICS_CHROMIUM"
BROWSERS = ("chromium", "chromium-browser", "google-chrome")
INSTALL_HINT = (
    "install Chromium on the server (Debian and Ubuntu: apt-get install chromium; the "
    f"Dockerfile has it) or set {BROWSER_VARIABLE} to a Chromium or Chrome executable, then "
    "restart it; the html export is the same sheet, to print from a browser"
)


class PdfUnavailable(Unavailable):
    """No Chromium to print with, or one that failed: the 503 ``pdf_unavailable`` problem."""

    code = "pdf_unavailable"


def browser() -> str | None:
    """The Chromium executable: ``KINEMATICS_CHROMIUM`` if set (None when it names nothing
    runnable), else the first of ``BROWSERS`` on PATH, else None."""
    configured = os.environ.get(BROWSER_VARIABLE, "").strip()
    if configured:
        return shutil.which(configured)
    return next((found for name in BROWSERS if (found := shutil.which(name))), None)


def require_browser() -> str:
    """The Chromium executable (``browser``), or ``PdfUnavailable`` saying what to install."""
    executable = browser()
    if executable is None:
        raise PdfUnavailable(f"no Chromium to print the PDF with: {INSTALL_HINT}")
    return executable


def html_to_pdf(html: str, timeout: float) -> bytes:
    """The PDF of a self-contained HTML document, printed by headless Chromium (A4 as the sheet's
    ``@page`` sets it, no header or footer): ``PdfUnavailable`` without a browser or when it
    fails, ``LimitExceeded`` past ``timeout`` seconds."""
    executable = require_browser()
    with tempfile.TemporaryDirectory(prefix="kinematics-pdf-") as work:
        folder = Path(work)
        sheet, pdf = folder / "sheet.html", folder / "sheet.pdf"
        sheet.write_text(html, encoding="utf-8")
        command = [
            executable, "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
            "--disable-extensions", "--disable-dev-shm-usage", "--no-pdf-header-footer",
            f"--user-data-dir={folder / 'profile'}", f"--print-to-pdf={pdf}", sheet.as_uri(),
        ]  # fmt: skip
        process = subprocess.Popen(
            command,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            start_new_session=True,  # its own group: a timeout kills the browser's children too
        )
        try:
            _, errors = process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            raise LimitExceeded(
                f"printing the PDF took more than {timeout:g} s; ask for fewer exercises"
            ) from None
        if process.returncode != 0 or not pdf.is_file():
            last = errors.decode("utf-8", "replace").strip().splitlines()[-1:] or ["no output"]
            raise PdfUnavailable(
                f"Chromium ({executable}) did not print the PDF (exit status "
                f"{process.returncode}: {last[0][:200]}): {INSTALL_HINT}"
            )
        return pdf.read_bytes()
