"""The solver's error hierarchy.

Every failure the solver can meet on user input is one of these; the server maps each class to a
stable problem+json ``code`` (see the scene-v1 spec). Messages state the numbers that show what is
wrong, for example ``|AC| = 0.4927 m > l2 + l3 = 0.47 m at crank angle 160 deg``.
"""

from __future__ import annotations


class KinematicsError(Exception):
    """Base class: a request the solver cannot answer, with a message for a person."""

    code = "kinematics_error"

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message


class InvalidScene(KinematicsError):
    """The document breaks the scene contract (unknown point, two grounds, zero-length link...)."""

    code = "invalid_scene"


class InvalidExpression(KinematicsError):
    """A time law is not an allowed expression; ``position`` is the 0-based offending character."""

    code = "invalid_expression"

    def __init__(self, message: str, position: int, expression: str = "") -> None:
        super().__init__(message)
        self.position = position
        self.expression = expression


class NotAssemblable(KinematicsError):
    """The linkage cannot be closed at the requested pose."""

    code = "not_assemblable"


class SingularConfiguration(KinematicsError):
    """The velocity equations are singular: the driver cannot move the linkage (dead centre)."""

    code = "singular_configuration"

    def __init__(self, message: str, condition_number: float) -> None:
        super().__init__(message)
        self.condition_number = condition_number


class LimitExceeded(KinematicsError):
    """The request is larger or longer than the solver allows."""

    code = "limit_exceeded"


class NoEvent(KinematicsError):
    """The requested event does not occur before ``t_max``."""

    code = "no_event"
