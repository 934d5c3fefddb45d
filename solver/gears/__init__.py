"""Gear trains (docs/GEARS.md): simple, compound, reverted and planetary trains and
differentials, as one linear system of Willis relations solved exactly.

``parse_gear_train`` reads a scene of kind ``gear_train``; ``analyze_gear_train`` and
``sweep_gear_train`` answer /analyze and /sweep with ``time_range``; ``willis_relation`` is the
mesh seen from its carrier.
"""

from solver.gears.analysis import analyze_gear_train, parse_gear_train, sweep_gear_train
from solver.gears.scene import GEAR_TRAIN_FIELDS, GearTrainScene
from solver.gears.train import degrees_of_freedom, willis_relation

__all__ = [
    "GEAR_TRAIN_FIELDS",
    "GearTrainScene",
    "analyze_gear_train",
    "degrees_of_freedom",
    "parse_gear_train",
    "sweep_gear_train",
    "willis_relation",
]
