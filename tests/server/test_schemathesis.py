"""schemathesis against the app's own OpenAPI document, in process (issue 15).

Every operation (29, one test each) gets schemathesis' coverage cases (the boundaries and
violations of each field the document describes, built as the tests are collected) and
``SCHEMATHESIS_EXAMPLES`` generated requests (derandomised: the same cases in every CI run):
about 10,000 requests in all (10,175 on 2026-12-01), no 5xx, and every error is problem+json
with a code. A longer run: ``SCHEMATHESIS_EXAMPLES=2000 .venv/bin/python -m pytest tests/server/test_schemathesis.py``
(about 40,000 cases).
"""  # noqa: E501

from __future__ import annotations

import json
import os

import schemathesis
from hypothesis import HealthCheck, settings
from schemathesis.checks import not_a_server_error

from server.app import app
from tests.server.test_fuzz import check

EXAMPLES = int(os.environ.get("SCHEMATHESIS_EXAMPLES", "60"))
OPENAPI = "/api/v1/openapi.json"


def app_schema() -> schemathesis.BaseSchema:
    """The document GET /api/v1/openapi.json serves (the app's ``openapi()`` as JSON), its
    requests sent to the app in process. Read without a request: ``from_asgi`` starts the app to
    ask for it (its workers' pool, about 5 s), in every pytest-xdist worker as it collects."""
    loaded = schemathesis.openapi.from_dict(json.loads(json.dumps(app.openapi())))
    loaded.app = app
    loaded.location = OPENAPI
    return loaded


schema = app_schema()


@schema.parametrize()
@settings(
    max_examples=EXAMPLES,
    derandomize=True,
    deadline=None,
    suppress_health_check=list(HealthCheck),
)
def test_the_api_as_documented(case: schemathesis.Case) -> None:
    response = case.call()
    case.validate_response(response, checks=[not_a_server_error])
    check(response)
