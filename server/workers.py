"""The solver's work in a bounded pool of worker processes, never on the event loop.

The server's one event loop only parses requests and moves bytes; every endpoint of a router
whose ``route_class`` is ``server.edge.WorkerRoute`` runs in one of ``workers`` processes
(``server.settings``). A request

1. waits for an idle worker, first come first served: at most ``queue`` requests wait, each
   at most ``queue_wait`` seconds; past either it is answered 503 with ``Retry-After`` (never a
   dropped connection);
2. runs its endpoint in the worker, which sends back the finished response (status, headers and
   body bytes; a solver error becomes its problem+json there);
3. is stopped when it runs past its endpoint's time limit (answered ``limit_exceeded`` with the
   limit) or when its client disconnects: the worker is killed and replaced, so a runaway
   request frees its core at once.

Before a request waits for a worker, its endpoint's ``front_check`` (``server.budget``) parses it
and estimates its work in the server's own process (one check at a time per client address:
``FrontChecks``): a bad or too costly request is refused at once, never queued. A request
estimated past ``LANE_SECONDS`` (or, without a check, on an endpoint whose time limit is above
``QUICK_LIMIT``) runs in the slow lane, which shares all the workers but one, so a cheap request
never waits behind an expensive one; and one client (by its address) holds at most
``settings.client_share`` places in the slow lane, past which it is answered 429 with
Retry-After, so two clients cannot shut out a third.
``/health`` and the static files never wait for a worker, so they answer while every worker is
busy. Workers are forked from a ``forkserver`` that has imported the app, so a replacement is
ready in milliseconds. With ``workers = 0``, with no pool started (an app driven without its
lifespan), or in a forked copy of the server, endpoints run in the server's thread pool as plain
FastAPI would run them. Like any multiprocessing program, a script that starts the app with its
lifespan must guard its main code with ``if __name__ == "__main__":`` (workers import it).
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import inspect
import logging
import math
import multiprocessing
import os
import signal
import time
from collections import deque
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from multiprocessing.connection import Connection
from typing import Any

from fastapi import Request as FastAPIRequest
from fastapi.encoders import jsonable_encoder
from fastapi.responses import JSONResponse
from starlette.concurrency import run_in_threadpool
from starlette.requests import Request
from starlette.responses import Response
from starlette.types import Receive

from server import budget, problems
from server.edge import CURRENT_REQUEST, FiniteJSONResponse, StrictJSONRoute
from server.settings import Settings
from solver.errors import KinematicsError, LimitExceeded

log = logging.getLogger("kinematics")
# Every endpoint that may run in a worker, by "METHODS path" (filled at import, in the server
# and, identically, in every worker).
ENDPOINTS: dict[str, Callable[..., Any]] = {}
# One BLAS thread per worker: the pool is the parallelism.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")

QUICK_LIMIT = 2.0  # s: endpoints with no check and this time limit or less use every worker
LANE_SECONDS = 0.5  # s of estimated work past which a request runs in the slow lane
Answer = tuple[int, list[tuple[bytes, bytes]], bytes]


class Busy(Exception):
    """No worker became free in time, or the queue is full (503), or the client already holds
    its share of the slow lane (429): answered with Retry-After."""

    def __init__(self, message: str, retry_after: int, status: int = 503) -> None:
        super().__init__(message)
        self.message, self.retry_after, self.status = message, retry_after, status


async def busy_problem(_: FastAPIRequest, error: Exception) -> JSONResponse:
    """The 503 or 429 answer, with Retry-After in seconds."""
    assert isinstance(error, Busy)
    code = "busy" if error.status == 503 else "too_many_requests"
    response = problems.problem(error.status, code, error.message)
    response.headers["Retry-After"] = str(error.retry_after)
    return response


def front_check(check: Callable[..., float]) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Give an endpoint its check: called with the endpoint's arguments in the server's process
    (in a thread) before the request waits for a worker, it raises the solver's errors (a bad
    or too costly request, answered at once) or returns the estimated seconds of work."""

    def attach(endpoint: Callable[..., Any]) -> Callable[..., Any]:
        endpoint.front_check = check  # type: ignore[attr-defined]
        return endpoint

    return attach


# --- in the worker -------------------------------------------------------------------------------


def answer(key: str, kwargs: dict[str, Any]) -> Answer:
    """Run one endpoint and return its finished response (errors as problem+json)."""
    try:
        result = ENDPOINTS[key](**kwargs)
        if not isinstance(result, Response):
            result = FiniteJSONResponse(jsonable_encoder(result))
    except KinematicsError as error:
        result = problems.solver_problem(error)
    except Exception as error:  # a defect: logged here, answered 500 like any other
        log.exception("unexpected error in a worker", exc_info=error)
        result = problems.internal_problem()
    return result.status_code, result.raw_headers, bytes(result.body)


def serve(connection: Connection, niceness: int) -> None:
    """A worker's loop: one request at a time until the server closes the pipe.

    The worker runs ``niceness`` below the server's CPU priority: on a machine whose cores are
    all busy the server's event loop (``/health``, reading requests, sending answers) is
    scheduled first instead of waiting for a worker's time slice to end."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C stops the server, which stops us
    os.nice(niceness)
    while True:
        try:
            key, kwargs = connection.recv()
        except (EOFError, OSError):
            return
        started = time.perf_counter()
        result = answer(key, kwargs)
        connection.send((result, time.perf_counter() - started))


# --- in the server ------------------------------------------------------------------------------


class Worker:
    """One worker process and the server's end of its pipe."""

    def __init__(self, context: Any, niceness: int) -> None:
        self.connection, child = context.Pipe()
        self.process = context.Process(target=serve, args=(child, niceness), daemon=True)
        self.process.start()
        child.close()

    def roundtrip(self, key: str, kwargs: dict[str, Any]) -> tuple[Answer, float]:
        """Send one request and wait for its answer and the seconds the worker spent on it (in
        a thread; EOFError if killed)."""
        self.connection.send((key, kwargs))
        result: tuple[Answer, float] = self.connection.recv()
        return result

    def stop(self) -> None:
        self.process.kill()
        self.process.join()
        self.connection.close()


async def _disconnected(receive: Receive) -> None:
    """Return when the client has gone (its request body was read already)."""
    while (await receive())["type"] != "http.disconnect":
        pass


class Pool:
    """``settings.workers`` worker processes, a bounded queue, time limits and replacement."""

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.owner = os.getpid()  # a forked copy of the app must not use this process's pool
        for name in THREAD_VARIABLES:
            os.environ.setdefault(name, "1")
        self.context = multiprocessing.get_context("forkserver")
        self.context.set_forkserver_preload(["server.app"])
        # Threads that wait on the workers' pipes (and start replacements).
        self.threads = ThreadPoolExecutor(2 * settings.workers + 2, "worker-pipe")
        self.idle: list[Worker] = []
        # Requests waiting for a worker, oldest first: a freed worker goes to the oldest.
        self.waiters: deque[asyncio.Future[Worker]] = deque()
        # Requests estimated past LANE_SECONDS (without a check: on endpoints allowed more than
        # QUICK_LIMIT s) share all workers but one, so a burst of them never holds back a cheap
        # request.
        self.slow_lane = asyncio.Semaphore(max(1, settings.workers - 1))
        # Places in the slow lane (running or waiting) by client address, with their estimates.
        self.slow_clients: dict[str, list[float]] = {}
        self.waiting = 0
        self.tasks: set[asyncio.Task[None]] = set()

    async def _in_thread(self, function: Callable[..., Any], *args: Any) -> Any:
        return await asyncio.get_running_loop().run_in_executor(self.threads, function, *args)

    async def start(self) -> None:
        for _ in range(self.settings.workers):
            self._release(await self._in_thread(Worker, self.context, self.settings.worker_nice))

    async def close(self) -> None:
        await asyncio.gather(*self.tasks, return_exceptions=True)
        while self.idle:
            await self._in_thread(self.idle.pop().stop)
        self.threads.shutdown(wait=False, cancel_futures=True)

    def _release(self, worker: Worker) -> None:
        """``worker`` is free: it goes to the request that has waited longest, else to idle."""
        while self.waiters:
            waiter = self.waiters.popleft()
            if not waiter.done():  # not cancelled (its client left, or it timed out)
                waiter.set_result(worker)
                return
        self.idle.append(worker)

    async def _take(self) -> Worker:
        """A worker, first come first served: an idle one only when nobody waits before us.

        Not an asyncio.Queue: there a request arriving just as a worker is freed takes it
        before the request woken for it runs, which then queues again at the back (a request
        could be passed over many times: the long tail of /analyze at 100 clients)."""
        if self.idle and not self.waiters:
            return self.idle.pop()
        waiter: asyncio.Future[Worker] = asyncio.get_running_loop().create_future()
        self.waiters.append(waiter)
        try:
            return await waiter
        except asyncio.CancelledError:
            if waiter.done() and not waiter.cancelled():  # handed a worker as it was cancelled
                self._release(waiter.result())
            raise

    def _replace(self, worker: Worker, lane: asyncio.Semaphore | None) -> None:
        """Kill ``worker`` and put a fresh one in its place (in the background); the place in
        ``lane`` it held is freed only then, so that a slow request waiting for the lane does
        not take the worker kept for cheap requests while the replacement starts."""

        async def replace() -> None:
            try:
                await self._in_thread(worker.stop)
                new = await self._in_thread(Worker, self.context, self.settings.worker_nice)
                self._release(new)
            finally:
                if lane is not None:
                    lane.release()

        task = asyncio.get_running_loop().create_task(replace())
        self.tasks.add(task)
        task.add_done_callback(self.tasks.discard)

    def _retry_after(self) -> int:
        return max(1, math.ceil(self.waiting / max(self.settings.workers, 1)))

    async def _acquire(
        self, gone: asyncio.Future[None], lane: asyncio.Semaphore | None
    ) -> Worker | None:
        """An idle worker (and a place in ``lane`` if given); None if the client left while
        waiting; Busy past the queue."""
        if self.waiting >= self.settings.queue:
            raise Busy(
                f"the server is busy: {self.waiting} requests wait for "
                f"{self.settings.workers} workers (at most {self.settings.queue}); retry later",
                self._retry_after(),
            )
        held = False

        async def take() -> Worker:
            nonlocal held
            if lane is not None:
                await lane.acquire()
                held = True
            return await self._take()

        self.waiting += 1
        get = asyncio.ensure_future(take())
        either: set[asyncio.Future[Any]] = {get, gone}
        try:
            done, _ = await asyncio.wait(
                either, timeout=self.settings.queue_wait, return_when="FIRST_COMPLETED"
            )
        finally:
            self.waiting -= 1
        if get in done:
            return get.result()
        get.cancel()
        with contextlib.suppress(asyncio.CancelledError):
            worker = await get  # it may have been handed a worker as it was cancelled
            self._release(worker)
        if held and lane is not None:
            lane.release()
        if gone in done:
            return None
        raise Busy(
            f"the server is busy: no worker became free within {self.settings.queue_wait:g} s; "
            "retry later",
            self._retry_after(),
        )

    def _enter_slow_lane(self, client: str, estimate: float) -> None:
        """Count a place in the slow lane for ``client``; Busy (429) past its share."""
        held = self.slow_clients.setdefault(client, [])
        if len(held) >= self.settings.client_share:
            raise Busy(
                f"this client already has {len(held)} slow requests running or waiting (at most "
                f"{self.settings.client_share} of the {max(1, self.settings.workers - 1)} "
                "workers that run slow requests); retry when one is answered",
                max(1, math.ceil(min(held))),
                429,
            )
        held.append(estimate)

    def _leave_slow_lane(self, client: str, estimate: float) -> None:
        held = self.slow_clients[client]
        held.remove(estimate)
        if not held:
            del self.slow_clients[client]

    async def run(
        self, key: str, kwargs: dict[str, Any], request: Request, estimate: float | None = None
    ) -> Response:
        """Run endpoint ``key`` in a worker within the time limit of ``request``'s path, in the
        slow lane if its ``estimate`` (seconds; None: not estimated) says so."""
        limit = self.settings.time_limit_of(request.url.path)
        slow = limit > QUICK_LIMIT if estimate is None else estimate > LANE_SECONDS
        lane = self.slow_lane if slow else None
        client = request.client.host if request.client else ""
        if lane is not None:
            estimate = limit if estimate is None else estimate
            self._enter_slow_lane(client, estimate)
        try:
            return await self._run(key, kwargs, request, limit, lane)
        finally:
            if lane is not None:
                assert estimate is not None
                self._leave_slow_lane(client, estimate)

    async def _run(
        self,
        key: str,
        kwargs: dict[str, Any],
        request: Request,
        limit: float,
        lane: asyncio.Semaphore | None,
    ) -> Response:
        gone = asyncio.ensure_future(_disconnected(request.receive))
        arrived = time.perf_counter()
        try:
            worker = await self._acquire(gone, lane)
        except Busy:
            gone.cancel()
            raise
        if worker is None:
            gone.cancel()
            return Response(status_code=499)  # nobody reads it: the client has left
        try:
            started = time.perf_counter()
            work = asyncio.ensure_future(self._in_thread(worker.roundtrip, key, kwargs))
            either: set[asyncio.Future[Any]] = {work, gone}
            done, _ = await asyncio.wait(either, timeout=limit, return_when="FIRST_COMPLETED")
            if work not in done or work.exception() is not None:
                work.add_done_callback(lambda w: w.exception())  # EOFError once killed
                self._replace(worker, lane)
                lane = None  # freed once the replacement is ready
                if gone in done:
                    return Response(status_code=499)
                if work not in done:
                    raise LimitExceeded(
                        f"the request ran past the time limit of {limit:g} s for "
                        f"{request.url.path} and was stopped"
                    )
                raise RuntimeError("a worker stopped while answering") from work.exception()
            self._release(worker)
            (status, headers, body), solve = work.result()
            response = Response(body, status_code=status)
            response.raw_headers = headers
            if self.settings.server_timing:
                queue, run = started - arrived, time.perf_counter() - started
                timing = ", ".join(
                    f"{name};dur={seconds * 1e3:.2f}"
                    for name, seconds in (("queue", queue), ("worker", run), ("solve", solve))
                )
                response.raw_headers = [*headers, (b"server-timing", timing.encode())]
            return response
        finally:
            gone.cancel()
            if lane is not None:
                lane.release()


class FrontChecks:
    """The checks of one client address run one at a time (in the server's threads): a client
    that sends many requests at once queues its own checks, and cannot hold more of the front
    process's CPU than any other client with a check to run."""

    def __init__(self) -> None:
        self.clients: dict[str, tuple[asyncio.Lock, int]] = {}  # lock, requests using it

    async def run(self, client: str, check: Callable[..., float], kwargs: dict[str, Any]) -> float:
        lock, users = self.clients.get(client, (asyncio.Lock(), 0))
        self.clients[client] = (lock, users + 1)
        try:
            async with lock:
                estimate: float = await run_in_threadpool(check, **kwargs)
                return estimate
        finally:
            lock, users = self.clients[client]
            if users == 1:
                del self.clients[client]
            else:
                self.clients[client] = (lock, users - 1)


FRONT_CHECKS = FrontChecks()


def offloaded(endpoint: Callable[..., Any], key: str) -> Callable[..., Any]:
    """``endpoint`` as an async endpoint that runs in the app's pool (same signature), after its
    ``front_check`` if it has one (in the server's process, whatever runs the endpoint)."""
    ENDPOINTS[key] = endpoint
    check: Callable[..., float] | None = getattr(endpoint, "front_check", None)

    @functools.wraps(endpoint)
    async def run(**kwargs: Any) -> Response:
        request = CURRENT_REQUEST.get()
        budget.SETTINGS.set(getattr(request.app.state, "settings", None))
        client = request.client.host if request.client else ""
        estimate = None if check is None else await FRONT_CHECKS.run(client, check, kwargs)
        pool: Pool | None = getattr(request.app.state, "pool", None)
        if pool is None or pool.owner != os.getpid():
            result: Response = await run_in_threadpool(endpoint, **kwargs)
            return result
        return await pool.run(key, kwargs, request, estimate)

    run.__signature__ = inspect.signature(endpoint)  # type: ignore[attr-defined]
    run.offloaded_from = endpoint  # type: ignore[attr-defined]
    return run


class WorkerRoute(StrictJSONRoute):
    """A strict-JSON route whose endpoint runs in the worker pool under its time limit.

    ``APIRouter(route_class=WorkerRoute, ...)`` is all a router needs. The endpoint's arguments
    (request models, query values) are pickled to the worker, so they must be picklable
    (module-level models); it should return a Response (anything else is sent as JSON).
    """

    def __init__(self, path: str, endpoint: Callable[..., Any], **kwargs: Any) -> None:
        original = getattr(endpoint, "offloaded_from", endpoint)  # when re-included with a prefix
        key = f"{','.join(sorted(kwargs.get('methods') or ['GET']))} {path}"
        super().__init__(path, offloaded(original, key), **kwargs)
