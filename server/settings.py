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
| ``KINEMATICS_SERVER_TIMING`` | 0 | 1: every response says how long the server spent on it (``Server-Timing``: in the app, waiting for a worker, the round trip to it, its own time), for load tests |
"""  # noqa: E501

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field

TIME_LIMITS = {
    "/api/v1/analyze": 2.0,
    "/api/v1/solution": 5.0,
    "/api/v1/solution.html": 5.0,
    "/api/v1/sweep": 10.0,
    "/api/v1/events": 10.0,
}


def usable_cores() -> int:
    """The cores this process may run on (a container's CPU set, not the host's count)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


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
    )
