"""schemathesis against the app's own OpenAPI document, in process (issue 15).

Every operation gets ``SCHEMATHESIS_EXAMPLES`` generated requests (derandomised: the same cases
in every CI run; about 2,000 in all): no 5xx, and every error is problem+json with a code. A
longer run: ``SCHEMATHESIS_EXAMPLES=2000 .venv/bin/python -m pytest tests/server/test_schemathesis.py``
(about 40,000 cases).
"""  # noqa: E501

from __future__ import annotations

import os

import schemathesis
from hypothesis import HealthCheck, settings
from schemathesis.checks import not_a_server_error

from server.app import app
from tests.server.test_fuzz import check

EXAMPLES = int(os.environ.get("SCHEMATHESIS_EXAMPLES", "60"))
schema = schemathesis.openapi.from_asgi("/api/v1/openapi.json", app)


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
