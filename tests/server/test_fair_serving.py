"""Fair serving (issue 28), over the real server on loopback (server.local).

A request is parsed and its work estimated in the server's own process before it waits for a
worker: a bad or too costly one is refused at once. A request estimated past the lane's
threshold runs in the slow lane (all the workers but one), so a cheap one never waits behind
it, and one client address holds at most its share of the slow lane (429 with Retry-After past
it). Clients are told apart by their addresses: loopback has a whole /8, so each client here
binds its own 127.0.0.x.
"""

from __future__ import annotations

import asyncio
import contextlib
import http.client
import json
import multiprocessing
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi import APIRouter, FastAPI

import solver
from server import budget
from server.routes.exercises import ExercisesRequest
from server.settings import Settings, from_environment
from server.workers import FRONT_CHECKS, LANE_SECONDS, WorkerRoute, front_check
from tests import run_apart
from tests.server.test_errors import FOUR_BAR
from tests.server.test_serving import NEWTON_RUNAWAY, server

# timed against servers of its own under load: run alone, after the others (tests/run.sh)
pytestmark = pytest.mark.serial

EXAMPLES = Path(__file__).resolve().parents[2] / "server" / "examples"
S003_T1 = json.loads((EXAMPLES / "S003-T1-translating-carrier.json").read_text())
# The issue's example: the crank turns 113,097 rad by t = 60 s (its law is 0.5236 t^3); it ran
# 10 s and then was answered 413 by the time limit.
ISSUE_EVENT = {"scene": S003_T1, "event": {"moving_point": "M", "reaches": "O1"}}
SWEEP_360 = {"scene": FOUR_BAR, "samples": 360}


def most_allowed(accepts: Callable[[int], object], most: int) -> int:
    """The largest n in 1..``most`` whose request the budget accepts (``accepts`` raises
    LimitExceeded past it), by bisection: the costliest legal request of a kind."""

    def ok(n: int) -> bool:
        try:
            accepts(n)
        except solver.errors.LimitExceeded:
            return False
        return True

    low, high = 1, most
    while low < high:
        middle = (low + high + 1) // 2
        low, high = (middle, high) if ok(middle) else (low, middle - 1)
    return low


NEWTON = solver.parse_scene(NEWTON_RUNAWAY["scene"])
MOST_SAMPLES = most_allowed(lambda n: budget.sweep(NEWTON, n, None), 100_000)  # type: ignore[arg-type]
MOST_FLYWHEELS = most_allowed(
    lambda n: budget.exercises("flywheel", n, True, "/api/v1/exercises"), 100
)
# The costliest legal requests of two kinds, found from the budget itself: the Newton-Raphson
# sweep of the largest group with the most samples it accepts, and the most flywheel exercises
# with worked solutions it accepts.
COSTLIEST = [
    ("/api/v1/sweep", {**NEWTON_RUNAWAY, "samples": MOST_SAMPLES}),
    (
        "/api/v1/exercises",
        {"type": "flywheel", "difficulty": "challenging", "count": MOST_FLYWHEELS,
         "with_solutions": True},
    ),
]  # fmt: skip


def _loop(base: str, address: str, stop: Any, answers: Any) -> None:
    """Post the costliest requests in turn from ``address`` until ``stop``; their statuses to
    ``answers``."""
    client = Client(base, address)
    with contextlib.closing(client.connection):
        while not stop.is_set():
            for path, body in COSTLIEST:
                if stop.is_set():
                    break
                client.connection.request(
                    "POST", path, json.dumps(body), {"content-type": "application/json"}
                )
                response = client.connection.getresponse()
                response.read()
                answers.put(response.status)


class Client:
    """One keep-alive connection from its own loopback address."""

    def __init__(self, base: str, address: str) -> None:
        host, port = base.removeprefix("http://").split(":")
        self.connection = http.client.HTTPConnection(
            host, int(port), timeout=60, source_address=(address, 0)
        )

    def post(self, path: str, body: Any) -> tuple[int, dict[str, str], Any]:
        self.connection.request(
            "POST", path, json.dumps(body), {"content-type": "application/json"}
        )
        response = self.connection.getresponse()
        raw = response.read()
        headers = {k.lower(): v for k, v in response.getheaders()}
        return (
            response.status,
            headers,
            json.loads(raw) if "json" in headers.get("content-type", "") else raw,
        )

    def close(self) -> None:
        self.connection.close()


@pytest.fixture(scope="module")
def two_workers() -> Iterator[str]:
    with server("fair", KINEMATICS_WORKERS="2", KINEMATICS_SERVER_TIMING="1") as base:
        yield base


def test_the_issues_event_search_is_refused_before_any_work_with_its_numbers() -> None:
    """The drivers' turn up to t_max is in the estimate: 113,097 rad x 12 ms for its dyad."""
    scene = solver.parse_scene(S003_T1)
    with pytest.raises(solver.errors.LimitExceeded) as refused:
        budget.event(scene, "M", 60.0, "O1")  # type: ignore[arg-type]
    assert "113,097 rad the drivers turn" in refused.value.message
    assert "more than the limit of 5 s (/api/v1/events's time limit of 10" in refused.value.message


def test_the_costliest_requests_are_legal_and_slow_and_the_sweep_is_cheap() -> None:
    """The lane test below drives requests the budget accepts; they run in the slow lane, the
    360-sample sweep in the fast one."""
    assert LANE_SECONDS < budget.sweep(NEWTON, MOST_SAMPLES, None) <= 5.0  # type: ignore[arg-type]
    with pytest.raises(solver.errors.LimitExceeded):
        budget.sweep(NEWTON, MOST_SAMPLES + 1, None)  # type: ignore[arg-type]
    path = "/api/v1/exercises"
    assert LANE_SECONDS < budget.exercises("flywheel", MOST_FLYWHEELS, True, path) <= 5.0
    with pytest.raises(solver.errors.LimitExceeded):
        budget.exercises("flywheel", MOST_FLYWHEELS + 1, True, path)
    assert budget.sweep(solver.parse_scene(FOUR_BAR), 360, None) < LANE_SECONDS  # type: ignore[arg-type]


def test_bad_and_too_costly_requests_are_refused_while_every_worker_is_busy(
    two_workers: str,
) -> None:
    """Both workers held by two clients' slow requests (the slow lane's one worker and a
    waiting request; then a cheap request on the other worker would still be answered): the
    issue's event search (413), a scene with a typo (422) and a body that is no JSON (422) are
    answered from the server's process, never queued (the slow requests are still pending)."""
    holders = [Client(two_workers, f"127.0.0.{n}") for n in (11, 12)]
    pending = []
    for holder in holders:
        holder.connection.request(
            "POST",
            "/api/v1/sweep",
            json.dumps(NEWTON_RUNAWAY),
            {"content-type": "application/json"},
        )
        pending.append(holder)
    try:
        client = Client(two_workers, "127.0.0.13")
        status, _, body = client.post("/api/v1/events", ISSUE_EVENT)
        assert status == 413 and "113,097 rad" in body["detail"], body
        typo = {"scene": {**FOUR_BAR, "drivres": []}, "strict": True}
        status, _, body = client.post("/api/v1/analyze", typo)
        assert status == 422 and body["code"] == "invalid_scene", body
        status, _, body = client.post("/api/v1/sweep", {"scene": FOUR_BAR, "samples": -3})
        assert status in (413, 422), body
        for holder in pending:  # still computing: nothing to read yet
            assert holder.connection.sock is not None
            holder.connection.sock.settimeout(0.01)
            with pytest.raises(TimeoutError):
                holder.connection.sock.recv(1)
        client.close()
    finally:
        for holder in holders:
            holder.close()


@pytest.mark.slow  # timed: a 1 s sleep stands for the first request reaching the pool
def test_one_client_holds_at_most_its_share_of_the_slow_lane(two_workers: str) -> None:
    """With two workers the slow lane is one worker and a client's share is one request: the
    same address's second slow request is answered 429 with Retry-After at once; another
    address's waits for the slow lane; a cheap request from the first address is answered."""
    first = Client(two_workers, "127.0.0.21")
    path, costliest_sweep = COSTLIEST[0]  # about 2 s of one core on a quiet machine
    first.connection.request(
        "POST", path, json.dumps(costliest_sweep), {"content-type": "application/json"}
    )
    try:
        time.sleep(1.0)  # the first slow request is in the pool (no timing asserted)
        again = Client(two_workers, "127.0.0.21")
        status, headers, body = again.post(*COSTLIEST[1])
        assert status == 429, body
        assert headers["content-type"].startswith("application/problem+json")
        assert (
            body["code"] == "too_many_requests" and "at most 1 of the 1 workers" in body["detail"]
        )
        assert int(headers["retry-after"]) >= 1
        status, _, _ = again.post("/api/v1/sweep", SWEEP_360)  # cheap: not counted
        assert status == 200
        again.close()
        assert first.connection.getresponse().status in (200, 413)
    finally:
        first.close()


@pytest.mark.slow  # timed: the issue's own requirement, with its outcome on the machine's load
def test_a_cheap_sweep_answers_within_a_second_while_two_clients_loop_the_costliest(
    two_workers: str,
) -> None:
    """The issue's lane test: two clients (two addresses) loop the costliest legal requests
    (each in turn: a Newton-Raphson sweep at the edge of the budget, the most flywheel
    exercises with solutions allowed) for the whole test, so the slow lane's worker is always
    busy and one request always waits for it; a third client's 360-sample /sweep is answered
    within 1 s, every time, 30 times. Measured on the shared 2-core machine at a load average
    of 8 to 10: see docs/SERVING.md ("Fair serving")."""
    context = multiprocessing.get_context("fork")
    stop = context.Event()
    answers = context.Queue()
    # In processes of their own: reading their large answers never holds this one's GIL.
    loopers = [
        context.Process(target=_loop, args=(two_workers, f"127.0.0.{n}", stop, answers))
        for n in (31, 32)
    ]
    for process in loopers:
        process.start()
    seconds: list[float] = []
    timings: list[str] = []  # the server's own account of each (Server-Timing)
    try:
        time.sleep(1.0)  # both loops have their first request in the pool
        third = Client(two_workers, "127.0.0.33")
        for _ in range(30):
            started = time.monotonic()
            status, headers, body = third.post("/api/v1/sweep", SWEEP_360)
            seconds.append(time.monotonic() - started)
            timings.append(headers.get("server-timing", ""))
            assert status == 200, body
        third.close()
    finally:
        stop.set()
        for process in loopers:
            process.join(timeout=120)
            if process.is_alive():
                process.kill()
    statuses = []
    while not answers.empty():
        statuses.append(answers.get())
    print(
        f"\n360-sample /sweep beside two looping clients: max {max(seconds):.3f} s, "
        f"median {sorted(seconds)[len(seconds) // 2]:.3f} s; loopers' answers {statuses}"
    )
    assert statuses and set(statuses) <= {200, 413, 503}  # done, past its limit, waited too long
    slowest = seconds.index(max(seconds))
    assert max(seconds) < 1.0, f"the cheap sweep took {max(seconds):.2f} s ({timings[slowest]})"


def test_a_clients_share_is_half_the_slow_lane_or_the_setting() -> None:
    """The slow lane is all the workers but one; a client's share half of it, at least 1."""
    assert [Settings(workers=n).client_share for n in (1, 2, 3, 5, 8, 9)] == [1, 1, 1, 2, 3, 4]
    assert from_environment({"KINEMATICS_CLIENT_SHARE": "4"}).client_share == 4
    with pytest.raises(ValueError, match="KINEMATICS_CLIENT_SHARE"):
        from_environment({"KINEMATICS_CLIENT_SHARE": "two"})


def test_one_clients_checks_run_one_at_a_time() -> None:
    """Six requests at once from one address: their front checks run one after another (a
    client cannot take more of the front process than another with a check to run)."""
    running, most = 0, {"one": 0}
    guard = threading.Lock()

    def check(request: ExercisesRequest) -> float:
        nonlocal running
        with guard:
            running += 1
            most[request.type] = max(most[request.type], running)
        time.sleep(0.05)  # a check that takes a while (an event search samples its law 2^18 times)
        with guard:
            running -= 1
        return 0.0

    router = APIRouter(route_class=WorkerRoute)

    @router.post("/checked")
    @front_check(check)
    def checked(request: ExercisesRequest) -> dict[str, str]:
        return {"type": request.type}

    app = FastAPI()
    app.include_router(router)

    async def burst(address: str, kind: str) -> list[int]:
        transport = httpx.ASGITransport(app=app, client=(address, 1234))
        async with httpx.AsyncClient(transport=transport, base_url="http://test") as client:
            answers = await asyncio.gather(
                *(client.post("/checked", json={"type": kind}) for _ in range(6))
            )
        return [a.status_code for a in answers]

    assert run_apart(burst("10.0.0.1", "one")) == [200] * 6
    assert most["one"] == 1
    assert FRONT_CHECKS.clients == {}  # nothing kept once answered
