"""What the endpoints answer: one instant, sweeps over a revolution or in time, events, and the
results' bodies."""
