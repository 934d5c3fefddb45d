"""The in-process client of the HTTP tests (fastapi.testclient).

``client`` drives the ASGI app in process, answering server errors as 500s.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from fastapi.testclient import TestClient

from server.app import app


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    # A server-side exception must reach the test as the 500 a user would get (a defect to
    # assert against), not as an exception re-raised into the test.
    with TestClient(app, raise_server_exceptions=False) as test_client:
        yield test_client
