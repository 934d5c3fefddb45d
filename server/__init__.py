"""The FastAPI edge of the kinematics solver: validate, convert, call the solver, convert back."""
