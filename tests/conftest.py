"""Shared fixtures: an in-process client and a live uvicorn server.

``client`` drives the ASGI app in process (fastapi.testclient), answering server errors as 500s.
``live_server`` starts the app the way a user does, ``python -m uvicorn server.app:app`` from the
repository root on a free loopback port, waits for GET /health, yields the base URL and stops the
process at the end of the session.
(tests/browser may define its own server fixture; this one is named ``live_server`` to stay apart.)
"""

from __future__ import annotations

import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO

import httpx
import pytest
from fastapi.testclient import TestClient

from server.app import app

ROOT = Path(__file__).resolve().parents[1]
STARTUP_TIMEOUT = 30.0  # s


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    # A server-side exception must reach the test as the 500 a user would get (a defect to
    # assert against), not as an exception re-raised into the test.
    with TestClient(app, raise_server_exceptions=False) as test_client:
        yield test_client


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        port: int = s.getsockname()[1]
        return port


@pytest.fixture(scope="session")
def live_server() -> Iterator[str]:
    port = _free_port()
    # output to a file: a pipe could fill up and block the server
    with tempfile.TemporaryFile() as log:
        yield from _serve(port, log)


def _serve(port: int, log: IO[bytes]) -> Iterator[str]:
    base = f"http://127.0.0.1:{port}"
    process = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "uvicorn",
            "server.app:app",
            "--host",
            "127.0.0.1",
            "--port",
            str(port),
            "--log-level",
            "warning",
        ],
        cwd=ROOT,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    try:
        deadline = time.monotonic() + STARTUP_TIMEOUT
        while True:
            if process.poll() is not None:
                log.seek(0)
                output = log.read().decode(errors="replace")
                pytest.fail(f"uvicorn exited with {process.returncode}:\n{output}")
            try:
                if httpx.get(f"{base}/health", timeout=1.0).status_code == 200:
                    break
            except httpx.TransportError:
                pass
            if time.monotonic() > deadline:
                pytest.fail(f"uvicorn did not answer GET /health within {STARTUP_TIMEOUT} s")
            time.sleep(0.1)
        yield base
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
