"""Security headers on every response, and CORS only when origins are configured.

The Content-Security-Policy allows scripts from this server only: no inline script and no
``unsafe-eval`` (KaTeX, Plotly and Swagger UI are vendored under /vendor; the pages start them
from script files). Inline styles stay allowed: KaTeX sets heights and offsets in style
attributes and Plotly injects its own style sheet. ``frame-ancestors 'none'`` (and
X-Frame-Options) forbid framing; ``nosniff`` stops a browser from guessing content types.
Cross-origin calls are refused by browsers unless ``KINEMATICS_CORS_ORIGINS`` lists the origin.
"""

from __future__ import annotations

from collections.abc import Callable

from fastapi import FastAPI
from starlette.middleware.cors import CORSMiddleware
from starlette.types import ASGIApp, Message, Receive, Scope, Send

from server.settings import Settings

CONTENT_SECURITY_POLICY = "; ".join(
    [
        "default-src 'self'",
        "script-src 'self'",
        "style-src 'self' 'unsafe-inline'",
        "img-src 'self' data: blob:",
        "font-src 'self' data:",
        "connect-src 'self'",
        "object-src 'none'",
        "base-uri 'none'",
        "form-action 'self'",
        "frame-ancestors 'none'",
    ]
)
HEADERS = [
    (b"content-security-policy", CONTENT_SECURITY_POLICY.encode()),
    (b"x-content-type-options", b"nosniff"),
    (b"x-frame-options", b"DENY"),
    (b"referrer-policy", b"no-referrer"),
]


Headers = list[tuple[bytes, bytes]]


async def edit_headers(
    app: ASGIApp, scope: Scope, receive: Receive, send: Send, edit: Callable[[Headers], Headers]
) -> None:
    """Run ``app`` with the headers of its HTTP response passed through ``edit`` (for the
    ASGI middlewares here and in ``server.timing``)."""
    if scope["type"] != "http":
        await app(scope, receive, send)
        return

    async def edited(message: Message) -> None:
        if message["type"] == "http.response.start":
            message = {**message, "headers": edit(list(message.get("headers", [])))}
        await send(message)

    await app(scope, receive, edited)


class SecurityHeaders:
    """ASGI middleware: add ``HEADERS`` to every HTTP response."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        await edit_headers(self.app, scope, receive, send, _with_security_headers)


def _with_security_headers(headers: Headers) -> Headers:
    present = {name.lower() for name, _ in headers}
    return [*headers, *((n, v) for n, v in HEADERS if n not in present)]


def install(app: FastAPI, settings: Settings) -> None:
    if settings.cors_origins:
        app.add_middleware(
            CORSMiddleware,
            allow_origins=list(settings.cors_origins),
            allow_methods=["GET", "POST"],
            allow_headers=["content-type"],
        )
    app.add_middleware(SecurityHeaders)
