"""The app factory: API routers under /api/v1, offline docs, health, and the static front end."""

from __future__ import annotations

from pathlib import Path

from fastapi import FastAPI
from fastapi.openapi.docs import get_swagger_ui_html
from fastapi.responses import HTMLResponse
from fastapi.staticfiles import StaticFiles

from server import problems
from server.routes import kinematics, presets, solution

STATIC = Path(__file__).resolve().parent.parent / "static"
API_PREFIX = "/api/v1"


def create_app() -> FastAPI:
    app = FastAPI(
        title="Kinematics of mechanisms",
        version="1.0.0",
        description="Planar linkages, moving points on moving bodies and spatial chains: "
        "positions, velocities, accelerations, poles, Coriolis, worked solutions. Scene format "
        "and contract: scene-v1.",
        docs_url=None,
        redoc_url=None,
        openapi_url=f"{API_PREFIX}/openapi.json",
    )
    problems.install(app)
    app.include_router(kinematics.router, prefix=API_PREFIX)
    app.include_router(presets.router, prefix=API_PREFIX)
    app.include_router(solution.router, prefix=API_PREFIX)

    @app.get(f"{API_PREFIX}/docs", include_in_schema=False)
    def docs() -> HTMLResponse:
        return get_swagger_ui_html(
            openapi_url=f"{API_PREFIX}/openapi.json",
            title="Kinematics API",
            swagger_js_url="/vendor/swagger-ui/swagger-ui-bundle.js",
            swagger_css_url="/vendor/swagger-ui/swagger-ui.css",
            swagger_favicon_url="/favicon.svg",
        )

    @app.get("/health", include_in_schema=False)
    def health() -> dict[str, str]:
        return {"status": "ok"}

    app.mount("/", StaticFiles(directory=STATIC, html=True), name="static")
    return app


app = create_app()
