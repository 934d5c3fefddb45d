# The kinematics teaching app: the same install as the README's first command (pinned deps,
# the project with its [server] extra).
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1

RUN useradd --create-home --uid 10001 app
# Chromium prints the exercise sheets to PDF (POST /api/v1/exercises/export with "format": "pdf",
# server/pdf.py), with fonts for its text; without it that export alone answers 503. Debian's
# package is not pinned: the archive replaces it with each security update.
# hadolint ignore=DL3008
RUN apt-get update \
    && apt-get install -y --no-install-recommends chromium fonts-liberation fonts-dejavu-core \
    && rm -rf /var/lib/apt/lists/*
WORKDIR /app

COPY pyproject.toml README.md requirements.lock ./
COPY solver ./solver
COPY server ./server
COPY static ./static
# The lock with its hashes (the library's dependencies and the [server] extra's), then the
# project with that extra and --no-deps (the lock already pinned them), then a check that the
# web app imports with what the lock installed.
RUN python -m pip install --no-cache-dir --require-hashes -r requirements.lock \
    && python -m pip install --no-cache-dir --no-deps "./[server]" \
    && python -c "import server.app"

USER 10001
EXPOSE 8000
HEALTHCHECK --interval=30s --timeout=3s --start-period=10s --retries=3 \
  CMD ["python", "-c", "import urllib.request, sys; sys.exit(0 if urllib.request.urlopen('http://127.0.0.1:8000/health', timeout=2).status == 200 else 1)"]
# One uvicorn process; the solver runs in KINEMATICS_WORKERS worker processes (default: the
# container's CPU quota from its cgroup, cpu.max or cpu.cfs_quota_us, rounded up, else its CPU
# set), with the queue and time limits of server/settings.py. Override with -e.
# The workers run 10 nice levels below the server: in its own container the event loop
# (/health) gets a core first (docs/SERVING.md, "What held /health back").
# The h11 protocol of server/deadlines.py answers 408 to a request whose headers and body do
# not arrive within KINEMATICS_REQUEST_TIMEOUT s; an idle kept-alive connection is closed after
# 5 s (uvicorn's --timeout-keep-alive). Behind a reverse proxy add --proxy-headers and
# --forwarded-allow-ips so that one client's share of slow work is counted by its own address.
ENV KINEMATICS_QUEUE=128 \
    KINEMATICS_WORKER_NICE=10 \
    KINEMATICS_QUEUE_WAIT=10 \
    KINEMATICS_TIME_LIMIT=10 \
    KINEMATICS_REQUEST_TIMEOUT=15
CMD ["uvicorn", "server.app:app", "--host", "0.0.0.0", "--port", "8000", "--http", "server.deadlines:DeadlineProtocol", "--timeout-keep-alive", "5", "--timeout-graceful-shutdown", "15"]
