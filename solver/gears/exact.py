"""Exact linear algebra over the rationals, for the structure of a gear train.

A train's relations have tooth ratios and ones for coefficients: reduced exactly
(``fractions.Fraction``), its rank, and so its degrees of freedom, carry no rounding tolerance,
and a train value comes out as the exact ratio a textbook prints (20/100, not 0.19999999).
The matrices are small (at most ``MAX_MEMBERS`` columns) and sparse; zeros are skipped.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction

Matrix = list[list[Fraction]]


def row_echelon(matrix: Sequence[Sequence[Fraction]], columns: int) -> tuple[Matrix, list[int]]:
    """The reduced row echelon form of ``matrix`` and its pivot columns, by Gauss-Jordan
    elimination in exact arithmetic; pivots are sought in the first ``columns`` columns only (the
    others, a right-hand side, are carried along). Rows are kept sparse (column -> entry): a
    train's relations have two or three entries each."""
    width = len(matrix[0]) if matrix else columns
    rows = [{j: Fraction(v) for j, v in enumerate(row) if v != 0} for row in matrix]
    pivots: list[int] = []
    done: list[dict[int, Fraction]] = []
    for column in range(columns):
        pick = next((i for i, row in enumerate(rows) if column in row), None)
        if pick is None:
            continue
        pivot_row = rows.pop(pick)
        lead = pivot_row[column]
        pivot_row = {j: v / lead for j, v in pivot_row.items()}
        for row in (*rows, *done):
            factor = row.get(column)
            if factor is None:
                continue
            for j, v in pivot_row.items():
                value = row.get(j, Fraction(0)) - factor * v
                if value:
                    row[j] = value
                else:
                    row.pop(j, None)
        pivots.append(column)
        done.append(pivot_row)
        if not rows:
            break
    dense = [[row.get(j, Fraction(0)) for j in range(width)] for row in done]
    return dense, pivots


def rank(matrix: Sequence[Sequence[Fraction]], columns: int) -> int:
    """The number of independent rows."""
    return len(row_echelon(matrix, columns)[1])


def null_space(matrix: Sequence[Sequence[Fraction]], columns: int) -> Matrix:
    """A basis of {x : matrix x = 0}, one vector per free column (1 there, 0 at the others)."""
    rows, pivots = row_echelon(matrix, columns)
    basis: Matrix = []
    for free in (j for j in range(columns) if j not in pivots):
        vector = [Fraction(0)] * columns
        vector[free] = Fraction(1)
        for row, pivot in zip(rows, pivots, strict=True):
            vector[pivot] = -row[free]
        basis.append(vector)
    return basis


def solve(matrix: Sequence[Sequence[Fraction]], rhs: Sequence[Fraction]) -> list[Fraction]:
    """The x of a square, non-singular system matrix x = rhs (the caller has checked the rank)."""
    size = len(rhs)
    augmented = [[*row, value] for row, value in zip(matrix, rhs, strict=True)]
    rows, _ = row_echelon(augmented, size)
    return [row[size] for row in rows]
