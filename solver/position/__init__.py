"""Solving a linkage's pose: the plan, the closed-form groups, the branch screen, constraints,
Newton-Raphson, continuation and polish."""
