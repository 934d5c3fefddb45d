"""Inverse dynamics of planar linkages (dynamics-v1): masses and loads, Newton-Euler, energy,
a cycle's figures and force balancing."""
