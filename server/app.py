"""The app factory: API routers under /api/v1, offline docs, health, and the static front end."""

from __future__ import annotations

from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

from fastapi import FastAPI
from fastapi.responses import FileResponse, HTMLResponse
from starlette.middleware.gzip import GZipMiddleware

from server import caching, headers, problems, schemas, workers
from server.routes import dynamics, exercises, kinematics, presets, solution, synthesis
from server.settings import Settings, from_environment
from server.static_files import PrecompressedFiles
from server.timing import ServerTiming

STATIC = Path(__file__).resolve().parent.parent / "static"
# The app's list of example scenes (file, title, description); the scenes are server/examples.
EXAMPLE_INDEX = Path(__file__).resolve().parent / "example_index.json"
API_PREFIX = "/api/v1"
GZIP_MINIMUM = 4096  # bytes: smaller answers (problems, one instant) are sent as they are
SWAGGER_PAGE = """<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>Kinematics API</title>
<link rel="icon" href="/favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="/vendor/swagger-ui/swagger-ui.css">
</head>
<body>
<div id="swagger-ui" data-openapi-url="{openapi}"></div>
<script src="/vendor/swagger-ui/swagger-ui-bundle.js"></script>
<script src="/js/swagger-init.js"></script>
</body>
</html>
"""


def create_app(settings: Settings | None = None) -> FastAPI:
    """The app; ``settings`` default to the environment's (server.settings)."""
    settings = from_environment() if settings is None else settings

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        """The worker pool lives as long as the server (none with ``workers = 0``)."""
        if settings.workers == 0:
            yield
            return
        pool = workers.Pool(settings)
        await pool.start()
        app.state.pool = pool
        try:
            yield
        finally:
            app.state.pool = None
            await pool.close()

    app = FastAPI(
        lifespan=lifespan,
        title="Kinematics of mechanisms",
        version="1.0.0",
        description="Planar linkages, moving points on moving bodies and spatial chains: "
        "positions, velocities, accelerations, poles, Coriolis, worked solutions. Scene format "
        "and contract: scene-v1.",
        docs_url=None,
        redoc_url=None,
        openapi_url=f"{API_PREFIX}/openapi.json",
        servers=[
            {
                "url": settings.public_url or "/",
                "description": "this server"
                if not settings.public_url
                else "the server's public address",
            }
        ],
    )
    app.state.settings = settings
    app.add_middleware(caching.Caching)  # inside gzip: the tags are of the identity body
    # Level 1: 13.5 MB of sweep JSON to 4.7 MB in 0.14 s of CPU (level 9: 4.4 MB in 1.3 s);
    # bodies past 128 KiB are compressed in a thread, off the event loop.
    app.add_middleware(GZipMiddleware, minimum_size=GZIP_MINIMUM, compresslevel=1)
    headers.install(app, settings)
    if settings.server_timing:  # outermost: the whole of the app's time
        app.add_middleware(ServerTiming)
    problems.install(app)
    _publish_problems(app)
    app.add_exception_handler(workers.Busy, workers.busy_problem)
    app.include_router(kinematics.router, prefix=API_PREFIX)
    app.include_router(presets.router, prefix=API_PREFIX)
    app.include_router(solution.router, prefix=API_PREFIX)
    app.include_router(exercises.router, prefix=API_PREFIX)
    app.include_router(dynamics.router, prefix=API_PREFIX)
    app.include_router(synthesis.router, prefix=API_PREFIX)

    @app.get(f"{API_PREFIX}/docs", include_in_schema=False)
    def docs() -> HTMLResponse:
        """Swagger UI from /vendor, started by a script file (no inline script: see CSP)."""
        return HTMLResponse(SWAGGER_PAGE.format(openapi=f"{API_PREFIX}/openapi.json"))

    @app.get(
        "/health",
        summary="Liveness: answered on the event loop, while every worker is busy",
        tags=["health"],
        response_model=schemas.Health,
        responses=schemas.FRONT_PROBLEMS,
    )
    async def health() -> dict[str, str]:
        """On the event loop: it answers while every worker is busy."""
        return {"status": "ok"}

    _serve_static(app)
    return app


def _publish_problems(app: FastAPI) -> None:
    """The OpenAPI document declares errors as application/problem+json and types the scene
    (server.schemas.publish)."""
    generate = app.openapi

    def openapi() -> dict[str, Any]:
        return schemas.publish(generate())

    app.openapi = openapi  # type: ignore[method-assign]


def _serve_static(app: FastAPI) -> None:
    """The front end: index.html at /, each folder of static/ mounted at its own path.

    Not one mount at "/": that would answer every unknown /api path itself (a 405 for a POST,
    a 404 for the wrong method on a real route) instead of the API's own 404 and 405. The example
    scenes at /examples are the one copy in server/examples (the OpenAPI page's examples too),
    listed for the app by /examples/index.json. Each folder's files are gzipped once a version
    (server.static_files), not once a client.
    """
    index = STATIC / "index.html"
    app.add_api_route(
        "/examples/index.json", _file_route(EXAMPLE_INDEX), methods=["GET"], include_in_schema=False
    )
    app.mount(
        "/examples",
        PrecompressedFiles(directory=schemas.EXAMPLES, minimum=GZIP_MINIMUM),
        name="examples",
    )

    @app.get("/", include_in_schema=False)
    def front_end() -> FileResponse:
        return FileResponse(index)

    for entry in sorted(STATIC.iterdir()):
        if entry.is_dir():
            files = PrecompressedFiles(directory=entry, minimum=GZIP_MINIMUM)
            app.mount(f"/{entry.name}", files, name=entry.name)
        elif entry.name != "index.html":
            app.add_api_route(
                f"/{entry.name}", _file_route(entry), methods=["GET"], include_in_schema=False
            )


def _file_route(path: Path) -> Callable[[], FileResponse]:
    def serve() -> FileResponse:
        return FileResponse(path)

    return serve


app = create_app()
