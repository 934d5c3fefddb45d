"""Worked solutions as data: steps in the textbook's form, built from the solver's own numbers."""

from solver.steps.model import Check, Mistake, Solution, Step, Value
from solver.steps.solve import METHODS, Method, solve

__all__ = ["METHODS", "Check", "Method", "Mistake", "Solution", "Step", "Value", "solve"]
