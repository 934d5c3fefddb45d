"""Parsing a scene document of either kind (the one place that dispatches on ``kind``)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from solver.errors import InvalidScene
from solver.scene import LinkageScene, parse_linkage
from solver.spatial import SpatialChain, parse_spatial_chain


def parse_scene(doc: Mapping[str, Any]) -> LinkageScene | SpatialChain:
    kind = doc.get("kind")
    if kind == "linkage":
        return parse_linkage(doc)
    if kind == "spatial_chain":
        return parse_spatial_chain(doc)
    raise InvalidScene(f"kind: expected 'linkage' or 'spatial_chain', got {kind!r}")


def parse_linkage_only(doc: Mapping[str, Any], endpoint: str) -> LinkageScene:
    scene = parse_scene(doc)
    if not isinstance(scene, LinkageScene):
        raise InvalidScene(f"kind: {endpoint} takes a 'linkage' scene")
    return scene
