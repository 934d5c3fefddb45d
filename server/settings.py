"""Serving settings, read once from the environment (the Dockerfile and the README use them).

| variable | default | meaning |
|---|---|---|
| ``KINEMATICS_WORKERS`` | the usable cores | worker processes that run the solver; 0 runs it in the server's threads (no time limits) |
| ``KINEMATICS_QUEUE`` | 128 | requests that may wait for a worker; one more is answered 503 with Retry-After |
| ``KINEMATICS_QUEUE_WAIT`` | 10 | seconds a request may wait for a worker before it is answered 503 |
| ``KINEMATICS_TIME_LIMITS`` | see ``TIME_LIMITS`` | ``/api/v1/sweep=20,/api/v1/analyze=1``: seconds of work per endpoint |
| ``KINEMATICS_TIME_LIMIT`` | 10 | seconds of work for an endpoint not listed |
| ``KINEMATICS_WORKER_NICE`` | 0 | how much lower the workers' CPU priority is than the server's (0 to 19), so the event loop (``/health``) never waits behind the solver for a core; 10 in the Dockerfile (a machine of its own) |
| ``KINEMATICS_CORS_ORIGINS`` | none | ``https://a.example,https://b.example``: origins allowed to call the API from a browser |
| ``KINEMATICS_CLIENT_SHARE`` | half the slow lane | slow requests one client address may have running or waiting (the slow lane is all the workers but one); past it 429 with Retry-After; 0: half the slow lane, at least 1 |
| ``KINEMATICS_REQUEST_TIMEOUT`` | 15 | seconds in which a request's headers and body must arrive (``server.deadlines``); past it 408 and the connection is closed |
| ``KINEMATICS_PUBLIC_URL`` | none | ``https://kinematics.example.edu``: the server named in the OpenAPI document (``servers``); none names ``/``, wherever the document is served |
| ``KINEMATICS_SERVER_TIMING`` | 0 | 1: every response says how long the server spent on it (``Server-Timing``: in the app, waiting for a worker, the round trip to it, its own time), for load tests |
"""  # noqa: E501

from __future__ import annotations

import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

TIME_LIMITS = {
    "/api/v1/analyze": 2.0,
    "/api/v1/solution": 5.0,
    "/api/v1/solution.html": 5.0,
    "/api/v1/sweep": 10.0,
    "/api/v1/events": 10.0,
}


CGROUP = Path("/sys/fs/cgroup")


def cpu_quota(cgroup: Path = CGROUP) -> float | None:
    """The CPUs a container's quota allows, quota / period: cgroup v2's ``cpu.max`` ("max
    100000" is no limit) or v1's ``cpu.cfs_quota_us`` / ``cpu.cfs_period_us`` (-1 is no
    limit); None where there is no quota or no cgroup file."""
    try:
        quota, _, period = (cgroup / "cpu.max").read_text().strip().partition(" ")
        return None if quota == "max" else int(quota) / int(period or 100_000)
    except (OSError, ValueError):
        pass
    for v1 in (cgroup / "cpu", cgroup / "cpu,cpuacct", cgroup):
        try:
            quota_us = int((v1 / "cpu.cfs_quota_us").read_text())
            period_us = int((v1 / "cpu.cfs_period_us").read_text())
        except (OSError, ValueError):
            continue
        return None if quota_us <= 0 or period_us <= 0 else quota_us / period_us
    return None


def usable_cores(cgroup: Path = CGROUP) -> int:
    """The cores this process may use: the container's CPU quota rounded up (a limit of 1.5
    CPUs gives 2 workers), at most the CPU set it may run on (``sched_getaffinity``), which
    alone is the answer where there is no quota."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    quota = cpu_quota(cgroup)
    return cores if quota is None else max(1, min(cores, math.ceil(quota)))


@dataclass(frozen=True)
class Settings:
    workers: int = field(default_factory=usable_cores)
    queue: int = 128
    queue_wait: float = 10.0
    time_limits: Mapping[str, float] = field(default_factory=lambda: dict(TIME_LIMITS))
    time_limit: float = 10.0
    worker_nice: int = 0
    cors_origins: tuple[str, ...] = ()
    server_timing: bool = False
    client_slow: int = 0  # 0: half the slow lane, at least 1 (``client_share``)
    request_timeout: float = 15.0
    public_url: str = ""  # the OpenAPI document's server; "" for "/" (where it is served)

    @property
    def client_share(self) -> int:
        """Slow requests one client may have running or waiting."""
        return self.client_slow or max(1, (self.workers - 1) // 2)

    def time_limit_of(self, path: str) -> float:
        """Seconds of work allowed for a request to ``path``."""
        return self.time_limits.get(path, self.time_limit)


def _number(env: Mapping[str, str], name: str, default: float, integer: bool = False) -> float:
    text = env.get(name, "").strip()
    if not text:
        return default
    try:
        value = int(text) if integer else float(text)
    except ValueError:
        kind = "a whole number" if integer else "a number"
        raise ValueError(f"{name}={text!r}: expected {kind}") from None
    if not value >= 0 or value == float("inf"):
        raise ValueError(f"{name}={text!r}: expected a finite number >= 0")
    return value


def _limits(text: str) -> dict[str, float]:
    limits = dict(TIME_LIMITS)
    for item in filter(None, (part.strip() for part in text.split(","))):
        path, _, seconds = (part.strip() for part in item.partition("="))
        value = _number({"KINEMATICS_TIME_LIMITS": seconds}, "KINEMATICS_TIME_LIMITS", 0.0)
        if not path.startswith("/") or value <= 0:
            raise ValueError(f"KINEMATICS_TIME_LIMITS: {item!r} is not /path=seconds, seconds > 0")
        limits[path] = value
    return limits


def _niceness(env: Mapping[str, str]) -> int:
    value = int(_number(env, "KINEMATICS_WORKER_NICE", Settings.worker_nice, integer=True))
    if value > 19:
        raise ValueError(f"KINEMATICS_WORKER_NICE={value}: expected 0 to 19")
    return value


def _switch(env: Mapping[str, str], name: str) -> bool:
    text = env.get(name, "").strip()
    if text not in ("", "0", "1"):
        raise ValueError(f"{name}={text!r}: expected 0 or 1")
    return text == "1"


def from_environment(env: Mapping[str, str] = os.environ) -> Settings:
    """The settings from ``KINEMATICS_*`` variables; ValueError names a bad one."""
    default = Settings()
    origins = env.get("KINEMATICS_CORS_ORIGINS", "")
    return Settings(
        workers=int(_number(env, "KINEMATICS_WORKERS", default.workers, integer=True)),
        queue=int(_number(env, "KINEMATICS_QUEUE", default.queue, integer=True)),
        queue_wait=_number(env, "KINEMATICS_QUEUE_WAIT", default.queue_wait),
        time_limits=_limits(env.get("KINEMATICS_TIME_LIMITS", "")),
        time_limit=_number(env, "KINEMATICS_TIME_LIMIT", default.time_limit),
        worker_nice=_niceness(env),
        cors_origins=tuple(o.strip() for o in origins.split(",") if o.strip()),
        server_timing=_switch(env, "KINEMATICS_SERVER_TIMING"),
        client_slow=int(_number(env, "KINEMATICS_CLIENT_SHARE", 0, integer=True)),
        request_timeout=_positive(env, "KINEMATICS_REQUEST_TIMEOUT", default.request_timeout),
        public_url=_url(env.get("KINEMATICS_PUBLIC_URL", "").strip()),
    )


def _url(text: str) -> str:
    if text and not text.startswith(("https://", "http://")):
        raise ValueError(f"KINEMATICS_PUBLIC_URL={text!r}: expected an http(s):// address")
    return text.rstrip("/")


def _positive(env: Mapping[str, str], name: str, default: float) -> float:
    value = _number(env, name, default)
    if value <= 0:
        raise ValueError(f"{name}={value:g}: expected a number of seconds > 0")
    return value
