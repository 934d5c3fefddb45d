"""Strict JSON documents: no duplicate keys, text that can be encoded, names that can be shown.

``loads`` parses a request body and checks the whole document once, before any work:

- a key may appear once per object (``{"scene": 1, "scene": 2}`` is refused, not "last wins");
- every string, key or value, is valid Unicode (a lone UTF-16 surrogate such as ``"\\udfff"``
  is valid JSON but cannot be encoded in UTF-8) and holds no control character except tab and
  line breaks (its length is bounded by the body's; a time law has its own limit);
- inside a ``scene``, every name (an object key, or the value of ``link``, ``point``, ``body``,
  ``name``, ...) is 1 to ``MAX_NAME`` printable characters: letters, digits, marks,
  punctuation, symbols and single spaces inside;
- nesting is at most ``MAX_DEPTH`` levels, numbers at most ``MAX_DIGITS`` digits.

Every refusal is ``InvalidScene`` with the path of the offending value (``scene.points.A``).
"""

from __future__ import annotations

import json
import unicodedata
from typing import Any

from solver.errors import InvalidScene

MAX_DEPTH = 32  # a scene is about 5 levels deep
MAX_NAME = 64  # characters of a name (the scene parser's own limit)
MAX_DIGITS = 400  # of a number literal: 1e400 is no longer a finite float anyway
# Keys whose string value is the name of a point, link, joint, body or moving point.
NAME_VALUES = frozenset(
    {"name", "link", "point", "body", "moving_point", "reaches", "center", "start", "through"}
)
# Of those, keys that may also hold coordinates (a mass's centre: dynamics-v1).
NAME_OR_VECTOR = frozenset({"center"})
# Keys whose list items are names.
NAME_LISTS = frozenset({"links", "points"})
_TEXT_CONTROLS = frozenset("\t\n\r")
_NAME_CATEGORIES = frozenset("LMNPS")


class _Pairs(dict[str, Any]):
    """An object whose key ``duplicate`` appeared more than once (reported with its path)."""

    duplicate: str


def _object(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    result = dict(pairs)
    if len(result) == len(pairs):
        return result
    marked, seen = _Pairs(result), set()
    for key, _ in pairs:
        if key in seen:
            marked.duplicate = key
            break
        seen.add(key)
    return marked


def _number(text: str) -> int:
    if len(text) > MAX_DIGITS:
        raise ValueError(f"a number has {len(text)} digits, more than {MAX_DIGITS}")
    return int(text)


def _reject_constant(name: str) -> Any:
    raise ValueError(f"{name} is not a number in JSON; send finite numbers only")


def loads(body: bytes | str) -> Any:
    """Parse and check a JSON document (see the module docstring); InvalidScene if it fails."""
    try:
        document = json.loads(
            body,
            object_pairs_hook=_object,
            parse_int=_number,
            parse_constant=_reject_constant,
        )
    except json.JSONDecodeError as error:
        raise InvalidScene(
            f"the body is not valid JSON: {error.msg} at line {error.lineno} column {error.colno}"
        ) from None
    except UnicodeDecodeError as error:
        raise InvalidScene(f"the body is not UTF-8: byte {error.start} cannot be decoded") from None
    except RecursionError:
        raise InvalidScene(f"the body is nested too deeply (at most {MAX_DEPTH} levels)") from None
    except ValueError as error:  # from _number or _reject_constant
        raise InvalidScene(f"the body is not strict JSON: {error}") from None
    check(document, "body", 0, in_scene=False)
    return document


def _text(value: str, path: str) -> None:
    for index, char in enumerate(value):
        category = unicodedata.category(char)
        if category == "Cs":
            raise InvalidScene(
                f"{path}: character {index} is a lone UTF-16 surrogate (U+{ord(char):04X}), "
                "which is not text; send valid Unicode"
            )
        if category == "Cc" and char not in _TEXT_CONTROLS:
            raise InvalidScene(
                f"{path}: character {index} is the control character U+{ord(char):04X}"
            )


def _name(value: str, path: str) -> None:
    if not value or len(value) > MAX_NAME:
        raise InvalidScene(
            f"{path}: a name has 1 to {MAX_NAME} characters, this one has {len(value)}"
        )
    for index, char in enumerate(value):
        if unicodedata.category(char)[0] not in _NAME_CATEGORIES and char != " ":
            raise InvalidScene(
                f"{path}: character {index} of the name {value!r} (U+{ord(char):04X}) is not "
                "allowed; a name holds letters, digits, marks, punctuation, symbols and spaces"
            )
    if value != value.strip() or "  " in value:
        raise InvalidScene(f"{path}: the name {value!r} has a leading, trailing or double space")


def check(value: Any, path: str, depth: int, in_scene: bool, key: str = "") -> None:
    """Check ``value`` (found at ``path`` under ``key``) and everything inside it."""
    if depth > MAX_DEPTH:
        raise InvalidScene(f"{path}: nested more than {MAX_DEPTH} levels deep")
    if isinstance(value, str):
        _text(value, path)
        if in_scene and key in NAME_VALUES:
            _name(value, path)
    elif (
        in_scene
        and key in NAME_VALUES
        and value is not None
        and not (key in NAME_OR_VECTOR and isinstance(value, list))
    ):
        raise InvalidScene(f"{path}: expected a name (a string), got {type(value).__name__}")
    elif isinstance(value, dict):
        if isinstance(value, _Pairs):
            raise InvalidScene(
                f"{path}: the key {value.duplicate!r} appears more than once; "
                "each key may appear once in an object"
            )
        for child_key, item in value.items():
            child = f"{path}.{child_key}" if path != "body" else child_key
            _text(child_key, f"{child} (the key)")
            child_in_scene = in_scene or child_key == "scene"
            if in_scene:
                _name(child_key, f"{child} (the key)")
            check(item, child, depth + 1, child_in_scene, child_key)
    elif isinstance(value, list):
        for index, item in enumerate(value):
            if in_scene and key in NAME_LISTS and isinstance(item, str):
                _name(item, f"{path}[{index}]")
            check(item, f"{path}[{index}]", depth + 1, in_scene)
