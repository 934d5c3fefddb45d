"""Kinematics of mechanisms: planar linkages, moving points on moving bodies, spatial chains.

A plain library (numpy, scipy, sympy; no web imports). A scene goes in, a frozen result comes out;
nothing here mutates a scene.
"""
