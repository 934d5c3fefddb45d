"""stub"""
from __future__ import annotations
from typing import Any
from solver.steps.model import Mistake


def linkage_mistakes(ctx: Any) -> list[Mistake]:
    return []


def spatial_mistakes(scene: Any, analysis: Any, fmt: Any) -> list[Mistake]:
    return []
