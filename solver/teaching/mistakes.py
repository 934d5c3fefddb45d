"""The catalogue of typical mistakes: one stable id per mistake, shared by the worked solutions
(their "typical mistakes", ``solver.solutions.mistakes``) and the exercise checker (its diagnosis,
``solver.exercises.mistakes``), so that grading and the worked solution name a mistake alike.

Each entry has its id (the ``kind`` of a solution's mistake, the ``mistake`` of a checked answer),
a title and a description. Where the mistake is a formula written wrong, the function below that
computes the wrong value is the one both outputs use, e.g. ``coriolis_without_factor_2``: the
Coriolis term a_Cor = 2 omega x v_rel written omega x v_rel.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace

import numpy as np

from solver.gears import GearTrainScene
from solver.kinematics.relative_motion import coriolis_acceleration
from solver.kinematics.rigid import Array, perp, rigid_body_acceleration


@dataclass(frozen=True)
class TypicalMistake:
    """A typical mistake: its stable id, its title and what it is."""

    id: str
    title: str
    description: str


_ENTRIES = (
    # --- the Coriolis term (worked solutions and exercises) ---
    TypicalMistake(
        "coriolis_without_factor_2",
        "The factor 2 in the Coriolis term",
        "a_Cor = 2 omega x v_rel written omega x v_rel.",
    ),
    TypicalMistake(
        "coriolis_left_out",
        "The Coriolis term left out",
        "a = a_transport + a_relative without 2 omega x v_rel, where the guide or carrier turns.",
    ),
    TypicalMistake(
        "coriolis_on_fixed_guide",
        "No Coriolis term on a fixed guide",
        "2 omega x v_rel written with the sliding link's omega on a guide fixed in the ground, "
        "whose omega (the one that belongs in it) is zero.",
    ),
    TypicalMistake(
        "coriolis.absolute_velocity",
        "Relative, not absolute, velocity in Coriolis",
        "2 omega x v written with the absolute velocity of the point for v_rel.",
    ),
    TypicalMistake(
        "coriolis.translating_carrier",
        "No Coriolis term on a translating carrier",
        "2 omega x v_rel written with the omega of the turning link that drives a carrier that "
        "only translates.",
    ),
    # --- rigid-body terms ---
    TypicalMistake(
        "alpha_in_normal_term",
        "alpha, not omega^2, in the normal term",
        "The normal term of an accelerating crank's pin written -alpha r for -omega^2 r.",
    ),
    TypicalMistake(
        "normal.sign",
        "The sign of the normal term -omega^2 r",
        "+omega^2 r for the normal (centripetal) term -omega^2 r.",
    ),
    TypicalMistake(
        "normal.alpha_squared",
        "omega squared, not alpha squared, in the normal term",
        "-alpha^2 r for the normal term -omega^2 r (seed 000 type 2, E000-T2-4).",
    ),
    TypicalMistake(
        "cross.order",
        "The order of the cross product",
        "r x omega for omega x r in the relative velocity (and r x alpha for alpha x r in the "
        "tangential acceleration).",
    ),
    TypicalMistake(
        "labels.omega_alpha",
        "alpha, not omega, in the tangential term",
        "omega x r for the tangential term alpha x r.",
    ),
    TypicalMistake(
        "unknowns.which_link",
        "Whose omega is unknown",
        "The driven link's known omega taken for the unknown omega of another link of a dyad.",
    ),
    # --- misread inputs (exercises) ---
    TypicalMistake(
        "rotation_sign",
        "The sense of a rotation",
        "A given rotation taken the other way round (counter-clockwise is positive).",
    ),
    TypicalMistake(
        "degrees_for_radians",
        "Degrees for radians",
        "Rates used or given in degrees where the formulas and the answer are in radians.",
    ),
    # --- gear trains (exercises) ---
    TypicalMistake(
        "internal_mesh_as_external",
        "The sign of an internal mesh",
        "An annulus and its pinion taken to turn opposite ways (-N_a/N_b, as an external pair), "
        "where they turn the same way (+N_a/N_b) seen from the carrier.",
    ),
    TypicalMistake(
        "relative_for_absolute",
        "A planet's speed relative to its carrier for its absolute speed",
        "omega_planet - omega_arm (the arm locked) taken for omega_planet, or the other way round.",
    ),
    # --- linkage synthesis (exercises) ---
    TypicalMistake(
        "degrees_as_radians",
        "Degrees read as radians",
        "An angle in degrees put into a cosine or a rotation e^(i phi) that takes radians (a "
        "calculator in radian mode).",
    ),
    TypicalMistake(
        "synthesis.chebyshev_spacing",
        "The Chebyshev spacing of the precision points",
        "The precision points taken at the ends and the middle of the range, not at "
        "x_j = (x0 + xf)/2 - (xf - x0)/2 cos((2j - 1) pi / 6).",
    ),
    TypicalMistake(
        "synthesis.freudenstein_sign",
        "The sign of K2 in Freudenstein's equation",
        "K1 cos theta_4 + K2 cos theta_2 + K3 = cos(theta_2 - theta_4) for "
        "K1 cos theta_4 - K2 cos theta_2 + K3: K2 (and the coupler from it) with the wrong sign.",
    ),
    TypicalMistake(
        "synthesis.signed_length",
        "A length from a negative K",
        "a = d/K1 (or c = d/K2) given with its sign: a negative K is a link pointing the other "
        "way, whose length is |d/K|.",
    ),
    TypicalMistake(
        "synthesis.k1_k2_swapped",
        "K1 = d/a and K2 = d/c swapped",
        "The crank and the rocker from the other texts' lettering (K1 = d/c, K2 = d/a) in this "
        "equation.",
    ),
    TypicalMistake(
        "synthesis.absolute_turn",
        "The coupler's turn from the first position",
        "A moving pivot carried to position j by the coupler's angle phi_j, not by its turn "
        "phi_j - phi_1 from the first position.",
    ),
    TypicalMistake(
        "synthesis.offset_side",
        "The offset along the bisector taken to the other side",
        "A fixed pivot placed at -d from the chord's midpoint: the offset is positive to the "
        "left of the chord's direction B1 -> B2 (C1 -> C2).",
    ),
    TypicalMistake(
        "synthesis.coupler_bisector",
        "The bisector of the coupler instead of the pivot's chord",
        "A fixed pivot placed on the perpendicular bisector of B1C1 (the coupler) rather than "
        "of B1B2 (the chord between B's two places), likewise D on that of C1B1, not C1C2.",
    ),
    # --- a point moving on a moving body ---
    TypicalMistake(
        "relative.carrier_rate",
        "No carrier rate in the relative velocity",
        "The carrier's rotation added to the relative velocity s-dot tau.",
    ),
    TypicalMistake(
        "relative.tangential_sense",
        "The sense of the tangential relative acceleration",
        "s-double-dot tau reversed (seed 003, task 1).",
    ),
    TypicalMistake(
        "relative.transport_point",
        "Transport velocity at M itself",
        "The transport velocity taken at the path's centre, not at the carrier's point at M.",
    ),
    # --- the other slips of the seeds (ERRATA.md) ---
    TypicalMistake(
        "position.trigonometry",
        "Trigonometry of the position: the right sides for the ratio",
        "cos phi from the wrong sides (seed 000 type 3, E000-T3-1).",
    ),
    TypicalMistake(
        "poles.wrong_velocity",
        "The pole from the velocity of the same point",
        "The velocity pole from a point with another point's velocity (E000-T1-5).",
    ),
    TypicalMistake(
        "inputs.rounding",
        "Rounding the inputs consistently",
        "Inputs rounded so that they describe another mechanism (E000-T2-6).",
    ),
    # --- the loop-closure method ---
    TypicalMistake(
        "loop.derivative_i",
        "d/dt e^(i theta) = i omega e^(i theta)",
        "The factor i of the derivative of e^(i theta) left out.",
    ),
    TypicalMistake(
        "loop.real_slider",
        "The slider's rates are real",
        "A spurious i in front of a slider's s-double-dot (seed 001, eq. 10).",
    ),
    # --- spatial chains ---
    TypicalMistake(
        "spatial.unit_vectors",
        "Cross products of unit vectors",
        "Unit vectors crossed out of their cyclic order.",
    ),
    TypicalMistake(
        "spatial.rigid_points",
        "Coriolis and relative terms of fixed points",
        "Coriolis and relative terms written for a point fixed in its body.",
    ),
    TypicalMistake(
        "spatial.axis_rate",
        "The turning axis in alpha",
        "rate (omega x e) left out of alpha where the axis turns with the body before it.",
    ),
    TypicalMistake(
        "spatial.centripetal_order",
        "The order in omega x (omega x r)",
        "(omega x r) x omega for the centripetal term omega x (omega x r).",
    ),
    # --- dynamics ---
    TypicalMistake(
        "dynamics.moment_about_accelerating_point",
        "Sum of moments about an accelerating point",
        "I_R alpha about an accelerating pin R without the r_RG x m a_G term (E004-7).",
    ),
    TypicalMistake(
        "weights_left_out",
        "The weights left out",
        "The driving torque or the pin forces without the links' weights m g.",
    ),
    TypicalMistake(
        "inertia_left_out",
        "The inertia forces left out",
        "The static answer: without -m a_G and -I_G alpha of the moving links.",
    ),
    TypicalMistake(
        "friction_left_out",
        "The friction left out",
        "The frictionless torque: without the Coulomb force at the slider (and the friction "
        "moments at the pins), which the driver must overcome as well.",
    ),
    TypicalMistake(
        "mean_torque_for_fluctuation",
        "The mean torque's work for the energy fluctuation",
        "2 pi |M_mean| taken for the largest swing of the energy over a revolution.",
    ),
    TypicalMistake(
        "flywheel_factor_two",
        "The flywheel's factor 2",
        "I_F = 2 Delta E / (k omega^2) from Delta E = (1/2) I k omega^2.",
    ),
    # --- cams: the chain rule (worked solutions and exercises) ---
    TypicalMistake(
        "cam_omega_left_out",
        "The cam's speed left out",
        "v = ds/dtheta for v = (ds/dtheta) omega (and a = d2s/dtheta2 for (d2s/dtheta2) omega^2): "
        "the derivatives in the cam angle taken for the rates in time.",
    ),
    # --- writing the answer down (exercises, any type) ---
    TypicalMistake(
        "magnitude_for_component",
        "A magnitude for a signed component",
        "|v_x| written for a negative v_x (or |omega| for a clockwise omega): the answer asks the "
        "component with its sign.",
    ),
    TypicalMistake(
        "action_reaction_sign",
        "The force on the other body",
        "F_12 written for F_21 = -F_12: the pin force the other body exerts, of the opposite sign.",
    ),
    TypicalMistake(
        "components_swapped",
        "The x and y components swapped",
        "v_y written for v_x and v_x for v_y.",
    ),
    TypicalMistake(
        "cam_beta_in_degrees",
        "The segment's duration in degrees",
        "ds/dtheta = h y'/beta with beta in degrees instead of radians (beta^2 in d2s/dtheta2).",
    ),
)

CATALOGUE: Mapping[str, TypicalMistake] = {m.id: m for m in _ENTRIES}


def typical_mistake(mistake_id: str) -> TypicalMistake:
    """The catalogue's entry of ``mistake_id`` (a KeyError for an id not in the catalogue)."""
    return CATALOGUE[mistake_id]


# --- the wrong values, one function per mistake that is a formula written wrong -----------------


def coriolis_without_factor_2(a_coriolis: Array) -> Array:
    """omega x v_rel for a_Cor = 2 omega x v_rel: a_Cor / 2."""
    return 0.5 * a_coriolis


def coriolis_left_out(a_coriolis: Array) -> Array:
    """No Coriolis term for a_Cor = 2 omega x v_rel: 0 a_Cor (zeros shaped like it)."""
    return 0.0 * a_coriolis


def coriolis_with_omega_of(omega_other: Array | float, v_rel: Array) -> Array:
    """2 omega_other x v_rel, with the omega of a link that is not the guide (or carrier) where
    a_Cor = 2 omega_guide x v_rel = 0: the mistakes ``coriolis_on_fixed_guide`` (the sliding
    link's omega) and ``coriolis.translating_carrier`` (the driving link's omega)."""
    return coriolis_acceleration(np.asarray(omega_other), v_rel)


def alpha_in_normal_term(a_A: Array, omega: float, alpha: float, r_AB: Array) -> Array:
    """a_B = a_A + alpha x r_AB - alpha r_AB for a_B = a_A + alpha x r_AB - omega^2 r_AB: the
    solver's rigid-body acceleration plus (omega^2 - alpha) r_AB."""
    right = rigid_body_acceleration(a_A, np.asarray(omega), np.asarray(alpha), r_AB)
    return right + (omega**2 - alpha) * r_AB


def normal_term_sign(a_A: Array, omega: float, alpha: float, r_AB: Array) -> Array:
    """a_B = a_A + alpha x r_AB + omega^2 r_AB for ... - omega^2 r_AB."""
    return a_A + alpha * perp(r_AB) + omega**2 * r_AB


def cross_order(v_A: Array, omega: float, r_AB: Array) -> Array:
    """v_B = v_A + r_AB x omega = v_A - omega x r_AB for v_A + omega x r_AB."""
    return v_A - omega * perp(r_AB)


def cross_order_acceleration(a_A: Array, omega: float, alpha: float, r_AB: Array) -> Array:
    """a_B = a_A + r_AB x alpha + (r_AB x omega) x omega = a_A - alpha x r_AB - omega^2 r_AB for
    a_A + alpha x r_AB - omega^2 r_AB: the tangential term reversed, the normal term unchanged
    (both of its cross products reversed)."""
    return rigid_body_acceleration(a_A, np.asarray(omega), np.asarray(-alpha), r_AB)


def omega_for_alpha(a_A: Array, omega: float, r_AB: Array) -> Array:
    """a_B = a_A + omega x r_AB - omega^2 r_AB for a_A + alpha x r_AB - omega^2 r_AB."""
    return a_A + omega * perp(r_AB) - omega**2 * r_AB


def alpha_squared(a_A: Array, omega: float, alpha: float, r_AB: Array) -> Array:
    """a_B = a_A + alpha x r_AB - alpha^2 r_AB for a_A + alpha x r_AB - omega^2 r_AB."""
    return a_A + alpha * perp(r_AB) - alpha**2 * r_AB


def rings_as_external(scene: GearTrainScene) -> GearTrainScene:
    """The train with every annulus taken as an external gear (``internal_mesh_as_external``):
    each internal mesh's Willis ratio +N_a/N_b written -N_a/N_b. Without its module, so that no
    centre distance is checked (an external pair could not sit where the annulus does)."""
    return replace(
        scene,
        gears=tuple(replace(g, internal=False) for g in scene.gears),
        meshes=tuple(replace(m, internal=False) for m in scene.meshes),
        module=None,
    )


def cam_rate_without_omega(rate: float, omega: float, order: int) -> float:
    """d^k s/dtheta^k for the rate d^k s/dt^k = (d^k s/dtheta^k) |omega|^k: rate / |omega|^k."""
    return rate / abs(omega) ** order


def cam_beta_in_degrees(rate: float, duration_deg: float, order: int) -> float:
    """The rate with beta in degrees in h y^(k) / beta^k: rate (beta_rad / beta_deg)^k."""
    return rate * (math.radians(duration_deg) / duration_deg) ** order
