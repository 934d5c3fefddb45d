"""The textbook formulas, vectorised over samples, with no solving: the rigid body, relative motion
with Coriolis, poles, instant centres, the four-bar's classification, spatial chains."""
