"""The app on a free loopback port, started the way a user starts it (for tests and benchmarks).

``serve_locally()`` runs ``python -m uvicorn server.app:app --host 127.0.0.1 --port <free>
--log-level warning --http server.deadlines:DeadlineProtocol`` (the Dockerfile's protocol: slow
clients are cut off) from the repository root in a subprocess, waits until GET /health answers
200, yields the base URL (``http://127.0.0.1:<port>``) and stops the process when the block ends,
whatever happens (terminate, then kill if it does not stop within 10 s)::

    with serve_locally() as base:
        urllib.request.urlopen(f"{base}/api/v1/presets")

The server's output goes to ``log`` (a binary file; a temporary file if None), never to a pipe
that could fill up and block it. If the server exits or does not answer within ``timeout``
seconds, RuntimeError is raised with its output (read back from ``log`` when that file is
readable and seekable, e.g. opened with ``"w+b"``).

Only the standard library is used here: no test or benchmark dependency is needed to import it.
"""

from __future__ import annotations

import contextlib
import http.client
import os
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import IO

__all__ = ["HOST", "ROOT", "serve_locally"]

ROOT = Path(__file__).resolve().parents[1]
HOST = "127.0.0.1"
STOP_TIMEOUT = 10.0  # s between terminate and kill
POLL_INTERVAL = 0.1  # s between two GET /health

# Straight to loopback: no http_proxy from the environment.
_opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))


@contextlib.contextmanager
def serve_locally(
    log: IO[bytes] | None = None, timeout: float = 40.0, settings: Mapping[str, str] | None = None
) -> Iterator[str]:
    """Run the app under uvicorn on a free 127.0.0.1 port and yield its base URL.

    ``settings``: environment variables for the server (``KINEMATICS_WORKERS``, ... see
    server/settings.py) on top of this process's environment.
    """
    with contextlib.ExitStack() as stack:
        out = log if log is not None else stack.enter_context(tempfile.TemporaryFile())
        start = _position(out)
        port = _free_port()
        base = f"http://{HOST}:{port}"
        command = [sys.executable, "-m", "uvicorn", "server.app:app"]
        command += ["--host", HOST, "--port", str(port), "--log-level", "warning"]
        command += ["--http", "server.deadlines:DeadlineProtocol"]
        process = subprocess.Popen(
            command,
            cwd=ROOT,
            stdin=subprocess.DEVNULL,
            stdout=out,
            stderr=subprocess.STDOUT,
            env={**os.environ, **(settings or {}), "PYTHONUNBUFFERED": "1"},
        )
        stack.callback(_stop, process)
        deadline = time.monotonic() + timeout
        while not _healthy(base):
            if process.poll() is not None:
                raise RuntimeError(
                    f"uvicorn exited with {process.returncode} before {base}/health answered:\n"
                    + _output(out, start)
                )
            if time.monotonic() > deadline:
                _stop(process)  # before reading the log back: it writes to the same file
                raise RuntimeError(
                    f"uvicorn did not answer GET {base}/health within {timeout:g} s:\n"
                    + _output(out, start)
                )
            time.sleep(POLL_INTERVAL)
        yield base


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind((HOST, 0))
        port: int = s.getsockname()[1]
        return port


def _healthy(base: str) -> bool:
    try:
        with _opener.open(f"{base}/health", timeout=1.0) as response:
            return bool(response.status == 200)
    except (OSError, http.client.HTTPException):  # URLError, refused, reset, timeout
        return False


def _stop(process: subprocess.Popen[bytes]) -> None:
    if process.poll() is not None:
        return
    process.terminate()
    try:
        process.wait(timeout=STOP_TIMEOUT)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def _position(log: IO[bytes]) -> int:
    try:
        return log.tell()
    except (OSError, ValueError):
        return 0


def _output(log: IO[bytes], start: int) -> str:
    """What the server wrote to `log` since `start` (it has stopped writing by now)."""
    try:
        log.flush()
        log.seek(start)
        text = log.read().decode(errors="replace")
    except (OSError, ValueError):  # io.UnsupportedOperation: opened write-only or a pipe
        name = getattr(log, "name", None)
        return f"(the output is in {name})" if isinstance(name, str) else "(output not readable)"
    return text or "(no output)"
