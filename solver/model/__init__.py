"""What a mechanism is: scene kinds and their parsers, time laws, quantities, the dynamics data.

The lowest layer of the solver: it imports nothing from the layers above (kinematics, position,
analysis, dynamics, teaching, solutions, exercises)."""
