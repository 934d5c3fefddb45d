"""Worked solutions as data: steps in the textbook's form, built from the solver's own numbers."""

from solver.solutions.model import Check, Mistake, Solution, Step, Value, solution_body
from solver.solutions.solve import METHODS, Method, solve

__all__ = [
    "METHODS",
    "Check",
    "Method",
    "Mistake",
    "Solution",
    "Step",
    "Value",
    "solution_body",
    "solve",
]
