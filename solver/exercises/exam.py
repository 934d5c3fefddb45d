"""Exam ids: opaque, unforgeable names of exercises whose keys stay with the instructor.

A practice id ``type:difficulty:seed:index`` is the whole exercise: anyone who has it can rebuild
the exercise and its key. An exam exercise is named instead by a token made with a deployment
secret ``K`` (``KINEMATICS_EXAM_SECRET``), a deterministic authenticated encryption of its
parameters p = (type, difficulty, seed, index) built from HMAC-SHA-256 alone (the SIV
construction, HMAC as the pseudo-random function):

    tag = HMAC(K_tag, p)[:16]        c = p XOR (HMAC(K_enc, tag || 0) || HMAC(K_enc, tag || 1) ...)
    id  = "exam-" + base64url(tag || c)

with K_tag, K_enc and K_gen = HMAC(K, label) for three distinct labels. Without K the id shows
nothing of p (c is p under a keystream only K_enc gives) and cannot be made up (the tag is a MAC
of p); with K the server opens it (``open_exam_id``) and serves the statement. The exercise itself
is drawn from a generator seeded with HMAC(K_gen, p), never with the id: the code is public, so a
generator seeded with anything a student holds would let them rebuild the key offline, and the
practice exercise of the same parameters is a different one.
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import hmac
import struct

from solver.errors import InvalidScene
from solver.exercises.model import DIFFICULTIES, ExerciseId

PREFIX = "exam-"
TAG_BYTES = 16
_BLOCK = hashlib.sha256().digest_size
_FIXED = struct.Struct(">QIB")  # seed, index, difficulty's position in DIFFICULTIES


class UnknownExamId(InvalidScene):
    """A token that is not the exam id of any exercise under this server's secret."""


def is_exam_id(text: str) -> bool:
    """Whether ``text`` has the form of an exam id (not whether it is a valid one)."""
    return text.startswith(PREFIX)


def _key(secret: bytes, label: bytes) -> bytes:
    return hmac.new(secret, b"kinematics exam " + label, hashlib.sha256).digest()


def _plain(ident: ExerciseId) -> bytes:
    difficulty = DIFFICULTIES.index(ident.difficulty)
    return _FIXED.pack(ident.seed, ident.index, difficulty) + ident.type.encode()


def _keystream(secret: bytes, tag: bytes, size: int) -> bytes:
    key = _key(secret, b"cipher")
    blocks = (size + _BLOCK - 1) // _BLOCK
    stream = b"".join(
        hmac.new(key, tag + i.to_bytes(4, "big"), hashlib.sha256).digest() for i in range(blocks)
    )
    return stream[:size]


def _xor(a: bytes, b: bytes) -> bytes:
    return bytes(x ^ y for x, y in zip(a, b, strict=True))


def _tag(secret: bytes, plain: bytes) -> bytes:
    return hmac.new(_key(secret, b"tag"), plain, hashlib.sha256).digest()[:TAG_BYTES]


def exam_id(ident: ExerciseId, secret: bytes) -> str:
    """``exam-`` + base64url(tag || c): the opaque name of the exam exercise ``ident``."""
    plain = _plain(ident)
    tag = _tag(secret, plain)
    token = tag + _xor(plain, _keystream(secret, tag, len(plain)))
    return PREFIX + base64.urlsafe_b64encode(token).decode().rstrip("=")


def open_exam_id(text: str, secret: bytes) -> ExerciseId:
    """The parameters named by an exam id, or ``UnknownExamId`` (forged, altered, or made under
    another secret: the tag does not match)."""
    unknown = UnknownExamId(f"id: {text[:80]!r} is not an exam exercise of this server")
    if not is_exam_id(text):
        raise unknown
    body = text[len(PREFIX) :]
    try:
        token = base64.urlsafe_b64decode(body + "=" * (-len(body) % 4))
    except (binascii.Error, ValueError):
        raise unknown from None
    if len(token) <= TAG_BYTES + _FIXED.size:
        raise unknown
    tag, cipher = token[:TAG_BYTES], token[TAG_BYTES:]
    plain = _xor(cipher, _keystream(secret, tag, len(cipher)))
    if not hmac.compare_digest(tag, _tag(secret, plain)):
        raise unknown
    # the tag holds: these are parameters this server encoded
    seed, index, difficulty = _FIXED.unpack(plain[: _FIXED.size])
    return ExerciseId(plain[_FIXED.size :].decode(), DIFFICULTIES[difficulty], seed, index)


def generator_seed(ident: ExerciseId, secret: bytes) -> str:
    """The seed of the exam exercise's generator: HMAC(K_gen, p), which only the server can
    make (see the module docstring)."""
    return hmac.new(_key(secret, b"generator"), _plain(ident), hashlib.sha256).hexdigest()
