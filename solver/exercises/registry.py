"""The registry of exercise types: every type by name, what it asks, how to draw it (a family of
``solver.exercises.families``, ``dynamics``, ``gear_trains``, ``cams`` or ``synthesis``) and which
typical mistakes apply.

Adding a type is one draw function in its family module and one entry here.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from solver.exercises import cams, dynamics, gear_trains, synthesis
from solver.exercises.families import (
    four_bar_acceleration,
    four_bar_poles,
    four_bar_velocity,
    inverted_slider_crank,
    moving_point,
    quick_return,
    slider_crank,
    slider_extension,
    spatial_arm,
)
from solver.exercises.model import Draft


@dataclass(frozen=True)
class ExerciseType:
    """A type of exercise: its name, what it is about, the keys it can ask, how to draw one,
    and the family of typical mistakes that apply to it (see ``solver.exercises.mistakes``)."""

    name: str
    title: str
    description: str
    asks: tuple[str, ...]
    draw: Callable[[random.Random, str], Draft]
    mistakes: str


def _type(
    name: str,
    title: str,
    description: str,
    asks: tuple[str, ...],
    draw: Callable[[random.Random, str], Draft],
    mistakes: str,
) -> ExerciseType:
    return ExerciseType(name, title, description, asks, draw, mistakes)


def _xy(key: str) -> tuple[str, str]:
    return (f"{key}_x", f"{key}_y")


_KINEMATIC_TYPES: tuple[ExerciseType, ...] = (
    _type(
        "four_bar_velocity", "Four-bar linkage: velocities",
        "A Grashof crank-rocker driven at a constant speed: the angular velocities of the "
        "coupler and the rocker, the velocity of C and (challenging) of a coupler point.",
        ("omega_coupler", "omega_rocker", *_xy("v_C"), *_xy("v_P")),
        four_bar_velocity, "four_bar",
    ),
    _type(
        "four_bar_acceleration", "Four-bar linkage: accelerations",
        "A Grashof crank-rocker, from standard on with an accelerating crank: the angular "
        "accelerations of the coupler and the rocker, the acceleration of C and "
        "(challenging) of a coupler point.",
        ("alpha_coupler", "alpha_rocker", *_xy("a_C"), *_xy("a_P")),
        four_bar_acceleration, "four_bar",
    ),
    _type(
        "four_bar_poles", "Four-bar linkage: poles of the coupler",
        "The coupler's velocity pole (instant centre) and, from standard on, its "
        "acceleration pole.",
        (*_xy("velocity_pole_coupler"), *_xy("acceleration_pole_coupler")),
        four_bar_poles, "four_bar",
    ),
    _type(
        "slider_crank", "Offset slider-crank",
        "The engine mechanism with an offset guide (centred at basic): the slider's velocity "
        "and acceleration, the rod's angular velocity and acceleration.",
        ("v_C_x", "omega_coupler", "a_C_x", "alpha_coupler"),
        slider_crank, "slider",
    ),
    _type(
        "inverted_slider_crank", "Inverted slider-crank: Coriolis",
        "A block on the crank pin slides in a turning slotted lever: the lever's angular "
        "velocity, the sliding velocity (basic), the lever's angular acceleration and the "
        "Coriolis acceleration 2 omega x v_rel.",
        ("omega_lever", *_xy("v_rel_A"), "alpha_lever", *_xy("a_cor_A")),
        inverted_slider_crank, "lever",
    ),
    _type(
        "quick_return", "Quick-return mechanism: Coriolis",
        "Crank and slotted lever driving a ram: the lever's angular velocity and the ram's "
        "velocity, the lever's angular acceleration, the Coriolis acceleration, and "
        "(challenging) the ram's acceleration.",
        ("omega_lever", "v_C_x", "alpha_lever", *_xy("a_cor_A"), "a_C_x"),
        quick_return, "quick_return",
    ),
    _type(
        "slider_extension", "Slider on a fixed guide with an extension",
        "A coupler whose point C slides on a fixed guide and whose extension D is asked: "
        "its angular velocity and acceleration, the velocity and acceleration of D.",
        ("omega_coupler", *_xy("v_D"), "alpha_coupler", *_xy("a_D")),
        slider_extension, "slider",
    ),
    _type(
        "moving_point", "Point moving on a moving body",
        "A point M moving by a time law in a groove of a turning disc or a slot of a turning "
        "rod: its velocity, Coriolis and absolute acceleration at an instant, and the time at "
        "which it reaches a point of its path.",
        (*_xy("v_M"), *_xy("a_cor_M"), *_xy("a_M"), "t_M_T"),
        moving_point, "moving_point",
    ),
    _type(
        "spatial_arm", "Spatial arm",
        "Three revolute joints in space: the angular velocity of the last body by "
        "composition, and the velocity and five-term acceleration of its tool point.",
        ("omega_3_x", "omega_3_y", "omega_3_z", "v_B_x", "v_B_y", "v_B_z", "a_B_x", "a_B_y",
         "a_B_z"),
        spatial_arm, "spatial",
    ),
)  # fmt: skip

TYPES: Mapping[str, ExerciseType] = {
    t.name: t
    for t in (
        *_KINEMATIC_TYPES,
        _type(
            "four_bar_torque", "Four-bar linkage: driving torque",
            "A Grashof crank-rocker of uniform bars: the torque that drives the crank at an "
            "instant (inverse dynamics, Newton-Euler), with weights, a load on the rocker and the "
            "pin force at B from standard on, an accelerating crank at challenging.",
            ("M_crank", "F_B_x", "F_B_y"), dynamics.four_bar_torque, "dynamics_torque",
        ),
        _type(
            "flywheel", "Four-bar linkage: flywheel",
            "The same four-bar at constant mean speed over a revolution: the largest fluctuation "
            "of the energy and the flywheel inertia for a coefficient of speed fluctuation k "
            "(weights and a load from standard on; the mean torque at challenging).",
            ("energy_fluctuation", "flywheel_inertia", "mean_torque"), dynamics.flywheel,
            "flywheel",
        ),
        _type(
            "holding_torque", "Four-bar linkage: holding torque (statics)",
            "A Grashof crank-rocker of uniform bars with a moment on its rocker, in statics: the "
            "torque on the crank that holds it in position, with the bars' weights and the pin "
            "force at B from standard on.",
            ("M_crank", "F_B_x", "F_B_y"), dynamics.holding_torque, "statics",
        ),
        _type(
            "slider_crank_friction", "Slider-crank with friction (statics)",
            "A massless slider-crank pushing a piston force with Coulomb friction at the slider: "
            "the driving torque with friction; from standard on with a friction circle at the "
            "crank pin and the torque without friction, at challenging with an offset guide and "
            "the guide's force on the slider.",
            ("M_crank", "M_0", "N_C_x", "N_C_y"), dynamics.slider_crank_friction, "friction",
        ),
        # gear trains (docs/GEARS.md): mistakes in solver.exercises.gear_trains
        _type(
            "planetary_output", "Planetary train: output speed",
            "A simple planetary train, the sun driven and the ring fixed: the arm's speed, from "
            "standard on the planet's, at challenging with the ring turning too.",
            ("omega_arm", "omega_planet"), gear_trains.planetary_output, "gear_train",
        ),
        _type(
            "differential_carrier", "Differential: carrier speed",
            "A spur-gear differential with both side gears driven: the carrier's speed, from "
            "standard on a planet's speed relative to it; at challenging a planetary "
            "differential (sun and ring driven).",
            ("omega_carrier", "omega_planet1_rel", "omega_arm", "omega_planet_rel"),
            gear_trains.differential_carrier, "gear_train",
        ),
        _type(
            "cam_follower_motion", "Cam: the follower's velocity and acceleration",
            "A disc cam with a translating roller follower, its rise and return by textbook "
            "laws: the follower's velocity and acceleration at a cam angle (the jerk at "
            "challenging), by the chain rule.",
            ("v", "a", "j"), cams.follower_motion, "cam",
        ),
        _type(
            "cam_pressure_angle", "Cam: pressure angle and radius of curvature",
            "A disc cam with an offset knife-edge or roller follower: the pressure angle at a "
            "cam angle, the cam surface's radius of curvature (standard), the smallest and largest "
            "pressure angles over the revolution (challenging).",
            ("phi", "rho", "phi_min", "phi_max"), cams.pressure_angle, "cam",
        ),
        # synthesis (docs/SYNTHESIS.md): built on a task of /synthesis, not on a scene; mistakes
        # in solver.exercises.synthesis_mistakes
        _type(
            "synthesis_function", "Function generator: Freudenstein's equation",
            "A four-bar generating y = f(x) over a range: Freudenstein's coefficients K1, K2, K3 "
            "at three precision points (given at basic, Chebyshev spacing from standard on), and "
            "from standard on the link lengths; decreasing ranges and other functions at "
            "challenging.",
            ("K1", "K2", "K3", "a", "b", "c"), synthesis.function_generator,
            "synthesis_function",
        ),
        _type(
            "synthesis_fixed_pivots", "Motion generation: the fixed pivots",
            "A coupler to guide through three positions, its moving pivots given: the fixed "
            "pivots A and D (the centre points; the first position at angle 0 at basic), and at "
            "challenging the pole P12.",
            ("A_x", "A_y", "D_x", "D_y", "P12_x", "P12_y"), synthesis.fixed_pivots,
            "synthesis_motion",
        ),
    )
}  # fmt: skip
