"""The library installs alone (issue 22): ``pip install .`` gives ``solver`` with numpy, scipy,
sympy and mpmath and no web framework; the web app's dependencies come with the ``[server]``
extra, which the hashed lock pins too.

The slow test builds a fresh venv (no system site packages), installs the four libraries from
their hashed lines of ``requirements.lock`` and the project with ``--no-deps``, and runs the
README's Python example there, so that neither the packaging nor the README can drift.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

from tests.test_locks import unpinned

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
LIBRARY = ("numpy", "scipy", "sympy", "mpmath")
WEB = ("fastapi", "pydantic", "uvicorn", "orjson", "starlette")


def readme_example() -> str:
    """The first ```python block under "## Use from Python" in the README."""
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Use from Python\n", 1)[1].split("\n## ", 1)[0]
    found = re.search(r"```python\n(.*?)```", section, re.DOTALL)
    assert found is not None, "README: no python block under 'Use from Python'"
    return found.group(1)


def locked(names: tuple[str, ...]) -> str:
    """The entries of requirements.lock for ``names`` (each pin with its hash lines)."""
    entries = re.split(r"\n(?=\S)", (ROOT / "requirements.lock").read_text())
    kept = [e for e in entries if e.split("==")[0].strip() in names and "==" in e]
    assert sorted(e.split("==")[0] for e in kept) == sorted(names)
    return "\n".join(kept) + "\n"


def test_the_library_requires_only_numpy_scipy_sympy_and_mpmath() -> None:
    names = sorted(canonicalize_name(Requirement(r).name) for r in PROJECT["dependencies"])
    assert names == sorted(LIBRARY)


def test_the_server_extra_brings_the_web_framework() -> None:
    names = {
        canonicalize_name(Requirement(r).name) for r in PROJECT["optional-dependencies"]["server"]
    }
    assert {"fastapi", "pydantic", "uvicorn", "orjson"} <= names


def test_the_lock_pins_the_library_and_the_server_extra() -> None:
    roots = [Requirement(r) for r in PROJECT["dependencies"]]
    roots += [Requirement(r) for r in PROJECT["optional-dependencies"]["server"]]
    assert unpinned(ROOT / "requirements.lock", roots) == []


def test_importing_the_solver_loads_no_web_package() -> None:
    code = f"import sys, solver\nprint(sorted(m for m in {WEB!r} if m in sys.modules))\n"
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True
    )
    assert out.stdout.strip() == "[]"


@pytest.fixture(scope="module")
def library_venv(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh venv with the four libraries (hashed, from the lock) and the project, built once
    for the module; its Python."""
    base = tmp_path_factory.mktemp("library-venv")
    subprocess.run([sys.executable, "-m", "venv", str(base / "venv")], check=True)
    python = base / "venv" / "bin" / "python"
    requirements = base / "library.lock"
    requirements.write_text(locked(LIBRARY))
    # --no-compile: the modules a test imports are compiled then (byte-compiling all of sympy
    # and scipy up front was two thirds of the install's time).
    pip = [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check"]
    pip.append("--no-compile")
    subprocess.run([*pip, "--require-hashes", "-r", str(requirements)], check=True)
    # A copy of the project: building it in place would leave build/ in the repository.
    source = base / "project"
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info", "build")
    for name in ("solver", "server"):
        shutil.copytree(ROOT / name, source / name, ignore=ignore)
    for name in ("pyproject.toml", "README.md"):
        shutil.copy(ROOT / name, source / name)
    subprocess.run([*pip, "--no-deps", str(source)], check=True)
    return python


def run_in(python: Path, code: str) -> subprocess.CompletedProcess[str]:
    """``code`` run by ``python`` outside the repository (the installed copy is imported)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    return subprocess.run(
        [str(python), "-c", code],
        cwd=python.parents[2],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )


@pytest.mark.slow
def test_the_installed_library_has_no_web_framework(library_venv: Path) -> None:
    code = (
        "import importlib.util\n"
        f"print([m for m in {WEB!r} if importlib.util.find_spec(m) is not None])\n"
    )
    out = run_in(library_venv, code)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


@pytest.mark.slow
def test_the_installed_library_has_every_requirement_it_declares(library_venv: Path) -> None:
    out = subprocess.run(
        [str(library_venv), "-m", "pip", "check"], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0, out.stdout + out.stderr


@pytest.mark.slow
def test_the_readme_python_example_runs_without_the_web_framework(library_venv: Path) -> None:
    code = "import solver, sys\nassert 'fastapi' not in sys.modules\n" + readme_example()
    code += "\nassert solver.__file__.startswith(sys.prefix), solver.__file__\nprint('ran')\n"
    out = run_in(library_venv, code)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().endswith("ran")
