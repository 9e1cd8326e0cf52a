"""cueplan: cue-sports shot planning on the Mathavan-Jackson-Parkin cushion-impact model.

The functions call the C++ libraries directly (cueplan._core, pybind11): no command
line and no server in between. SI units (m, kg, s, m/s, rad/s), angles in degrees, spins
in the paper's dimensionless form k = w R / V. Bad input raises InputError (a
ValueError) whose ``field`` names the argument or the problem file's field. Every long
computation releases the GIL, so Python threads run in parallel with it.

    import cueplan
    problem = cueplan.Problem("problems/one_rail_position.yaml")
    plan = cueplan.solve(problem)
    plan.shot.plot()
    t, x, y = plan.shot.trajectory(0.01)
    cueplan.rebound(np.full(10**5, 1.0), np.linspace(1, 179, 10**5))
"""
from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _core
from ._core import InputError
from ._problem import Ball, Pocket, Problem, ProblemLike, Table, as_problem
from ._shot import Plan, Shot, SpinMap, Stroke, StrokeLike, Trajectory, as_stroke, record_of
from ._tables import default_cache_dir, table_for

__version__ = "0.1.0"

__all__ = [
    "InputError", "Ball", "Pocket", "Problem", "Table", "Stroke", "Shot", "Trajectory", "Plan",
    "SpinMap", "rebound", "collide", "simulate", "solve", "solve_many", "spin_map",
    "default_cache_dir", "__version__",
]

ArrayLike = Union[float, Sequence[float], np.ndarray]
PathLike = Union[str, "os.PathLike[str]"]


def _columns(*values: ArrayLike):
    """The arguments broadcast together, as contiguous float64 rows, with their shape."""
    arrays = np.broadcast_arrays(*[np.asarray(v, dtype=np.float64) for v in values])
    shape = arrays[0].shape
    return [np.ascontiguousarray(a.reshape(-1)) for a in arrays], shape


def _shaped(result: Dict[str, np.ndarray], names: Sequence[str], shape) -> Dict[str, Any]:
    status = np.asarray(names)[result.pop("status")]
    result["status"] = status
    if shape == ():
        return {k: (v[0].item() if isinstance(v[0], np.generic) else v[0]) for k, v in result.items()}
    return {k: v.reshape(shape) for k, v in result.items()}


def rebound(speed: ArrayLike, angle: ArrayLike, topspin_k: ArrayLike = 1.0, sidespin_k: ArrayLike = 0.0, *,
            method: str = "exact", model: str = "mathavan_2010", mass: float = 0.1406,
            radius: float = 0.02625, cushion_height: Optional[float] = None, mu_cushion: float = 0.14,
            mu_table: float = 0.212, restitution: float = 0.98, rigid_speed_limit: float = 2.5,
            tolerance: float = 1e-12, steps: int = 5000, max_steps: int = 10000, lanes: int = 0,
            threads: int = 0, table_cache: Optional[PathLike] = None) -> Dict[str, Any]:
    """A ball's rebound off a cushion, for every row of numpy arrays (broadcast together).

    speed: incoming speed V0 (m/s, > 0); angle: incidence alpha (deg, in (0, 180), 90 is
    head-on); topspin_k, sidespin_k: the spins k = w R / V0 (topspin 1 is natural roll;
    sidespin > 0 right). The ball: mass (kg), radius (m); the cushion: cushion_height
    (m above the cloth, default 7R/5), mu_cushion, mu_table (ball-cloth friction),
    restitution (energetic, in (0, 1]), rigid_speed_limit (m/s; normal speeds above it are
    flagged rigid_limit_exceeded); model mathavan_2010 or han_2005. method: exact,
    extrapolation, paper (steps: its N) or table (the impact table, cached in table_cache);
    tolerance: the exact methods' local error. Rows run side by side in SIMD lanes
    (lanes: 0 the widest the CPU has) on `threads` threads (0: one per core).

    Returns columns (arrays of the inputs' shape, floats for scalar inputs):
    rebound_speed (m/s), rebound_angle_deg (deg from the cushion, as alpha), vx, vy (m/s,
    cushion frame: x along the cushion, y into it), wx, wy, wz (rad/s), impulse_total
    (N s), work_total (J), status (ok, rigid_limit_exceeded, step_limit; NaN results for
    step_limit rows). A bad row raises InputError naming its column (field "angle").
    """
    params = _core.CushionParams(float(mass), float(radius), cushion_height, float(mu_cushion),
                                 float(mu_table), float(restitution), float(rigid_speed_limit), model)
    table = table_for(params, table_cache) if method == "table" else None
    (v, a, kt, ks), shape = _columns(speed, angle, topspin_k, sidespin_k)
    result = _core.rebound(v, a, kt, ks, params, method, float(tolerance), int(steps), int(max_steps),
                           int(lanes), int(threads), table, shape == ())
    return _shaped(result, _core.IMPACT_STATUS, shape)


def collide(speed: ArrayLike, cut: ArrayLike, topspin_k: ArrayLike = 1.0, sidespin_k: ArrayLike = 0.0, *,
            model: str = "mathavan_2014", friction: str = "constant", method: str = "exact",
            mass: float = 0.1406, radius: float = 0.02625, mu_ball: float = 0.05,
            restitution: float = 0.89, mu_table: float = 0.212, tolerance: float = 1e-12,
            steps: int = 5000, max_steps: int = 10000, threads: int = 0) -> Dict[str, Any]:
    """A cue ball striking an object ball at rest, for every row of numpy arrays.

    speed: the cue ball's speed (m/s, > 0) along +x; cut: the cut angle (deg, |cut| < 90,
    0 full ball, > 0 cuts the object ball to the right); topspin_k, sidespin_k: its spins
    k = w R / V (1 natural roll). model mathavan_2014 (friction between the balls and at
    the cloth) or frictional_inelastic (closed form; friction constant or
    speed_dependent); method exact, paper (steps: its N) or extrapolation; mu_ball,
    restitution (e_b), mu_table (ball-cloth), mass (kg), radius (m).

    Returns columns: cue_* and object_* (vx, vy in m/s, wx, wy, wz in rad/s, rolling_vx,
    rolling_vy, rolling_speed in m/s and rolling_angle_deg: the velocity once rolling),
    throw_deg (the object ball's direction against the line of centres), impulse_total
    (N s), status (ok, step_limit).
    """
    params = _core.BallBallParams(float(mass), float(radius), float(mu_ball), float(restitution),
                                  float(mu_table), model, friction)
    (v, c, kt, ks), shape = _columns(speed, cut, topspin_k, sidespin_k)
    result = _core.collide(v, c, kt, ks, params, method, float(tolerance), int(steps), int(max_steps),
                           int(threads), shape == ())
    return _shaped(result, _core.COLLISION_STATUS, shape)


def _table(problem: Problem, method: str, table_cache: Optional[PathLike]):
    if method != "table":
        return None, method
    table = table_for(problem._core.cushion_params, table_cache)
    # A han_2005 cushion resolves every impact in closed form: the method plays no part.
    return table, ("table" if table is not None else "exact")


def simulate(problem: ProblemLike, stroke: StrokeLike, *, method: str = "exact",
             accuracy: Optional[float] = None, max_events: int = 200,
             table_cache: Optional[PathLike] = None) -> Shot:
    """One stroke on a problem's table, every ball to rest.

    problem: a Problem, a problem file's path, its text or a dict of its fields; stroke: a
    Stroke, a dict of its fields or (speed, aim_deg[, topspin_k[, sidespin_k[,
    elevation_deg]]]) (m/s, deg, k, k, deg). method: the cushion impacts' (exact,
    extrapolation, paper, or table: the cached impact table); accuracy: the relative error
    wanted from each impact (default 1e-9, or the table's measured error); max_events:
    bound on the events of all balls.
    """
    p = as_problem(problem)
    s = as_stroke(stroke)
    table, method = _table(p, method, table_cache)
    core = _core.simulate(p._core, s.speed, s.aim_deg, s.topspin_k, s.sidespin_k, s.elevation_deg, method,
                          accuracy, int(max_events), table)
    return Shot(core, p)


def _options(seed: int, max_evaluations: int, max_time: float, starts: int, samples: int, noise: float,
             robust: bool, alternatives: int, global_method: str, local_method: str,
             enforce_rigid_limit: bool, threads: int):
    return _core.planner_options(int(seed), int(max_evaluations), float(max_time), int(starts), int(samples),
                                 float(noise), bool(robust), int(alternatives), global_method, local_method,
                                 bool(enforce_rigid_limit), int(threads))


def solve(problem: ProblemLike, *, seed: int = 1, max_evaluations: int = 2000, max_time: float = 10.0,
          starts: int = 6, samples: int = 200, noise: float = 1.0, robust: bool = False,
          alternatives: int = 5, global_method: str = "crs2", local_method: str = "bobyqa",
          method: str = "table", accuracy: Optional[float] = None, max_events: int = 200,
          enforce_rigid_limit: bool = False, threads: int = 1,
          table_cache: Optional[PathLike] = None) -> Plan:
    """Plans a problem: the stroke (speed, aim, spin) that solves it, its chances under a
    player's execution noise, and the other ways found.

    seed: every random choice derives from it (same seed and options, same answer while
    the evaluation budget, not max_time, ends the search); max_evaluations: shot
    simulations for the search; max_time: wall-clock budget (s); starts: candidates
    polished locally; samples: noisy strokes per success estimate (0: none); noise: the
    player's scatter, times a club player's (0-10); robust: maximise the success chance
    rather than the nominal miss; alternatives: other ways returned; global_method
    (direct_l, crs2, mlsl, isres, ompl_kpiece1) and local_method (bobyqa, sbplx, cobyla,
    neldermead); method: cushion impacts (table, the command line's default, exact, ...);
    accuracy, max_events: as simulate's; threads: local polishes in parallel (0: one per
    core; the answer does not change).
    """
    p = as_problem(problem)
    options = _options(seed, max_evaluations, max_time, starts, samples, noise, robust, alternatives,
                       global_method, local_method, enforce_rigid_limit, threads)
    table, method = _table(p, method, table_cache)
    return Plan(_core.plan(p._core, options, method, accuracy, int(max_events), table), p, method)


def solve_many(problems: Sequence[ProblemLike], *, threads: int = 0, seed: int = 1,
               max_evaluations: int = 2000, max_time: float = 10.0, starts: int = 6, samples: int = 200,
               noise: float = 1.0, robust: bool = False, alternatives: int = 0,
               global_method: str = "crs2", local_method: str = "bobyqa", method: str = "table",
               accuracy: Optional[float] = None, max_events: int = 200, enforce_rigid_limit: bool = False,
               table_cache: Optional[PathLike] = None) -> List[Dict[str, Any]]:
    """Plans every problem, `threads` at a time (0: one per core; each plan on one
    thread, so the answers are those of solve(..., threads=1)), and returns one record
    (a flat dict) per problem in their order, for pandas.DataFrame(records): name,
    status, speed, aim_deg, topspin_k, sidespin_k, elevation_deg, success (P of the whole
    shot), p_pot, p_position, miss_distance, final_x, final_y (m), cushion_hits, family,
    evaluations, time_s, message. Options as solve's.
    """
    ps = [as_problem(p) for p in problems]
    options = _options(seed, max_evaluations, max_time, starts, samples, noise, robust, alternatives,
                       global_method, local_method, enforce_rigid_limit, 1)
    tables, methods = zip(*[_table(p, method, table_cache) for p in ps]) if ps else ((), ())
    results = _core.plan_many([p._core for p in ps], options, list(methods), accuracy, int(max_events),
                              list(tables), int(threads))
    return [record_of(r) for r in results]


def spin_map(problem: ProblemLike, speed: Optional[float] = None, aim_deg: Optional[float] = None, *,
             grid: int = 41, spin_max: float = 0.0, threads: int = 0, method: str = "table",
             accuracy: Optional[float] = None, max_events: int = 200,
             table_cache: Optional[PathLike] = None) -> SpinMap:
    """Where every spin within the miscue limit sends the cue ball for one speed (m/s)
    and aim (deg): a grid x grid square over the tip-offset disc of radius spin_max (0:
    the problem's spin limit), each simulated (a pot problem's aim solved again per spin).
    Without speed and aim, the planner's stroke (solve with its defaults)."""
    p = as_problem(problem)
    if speed is None or aim_deg is None:
        stroke = solve(p, method=method, table_cache=table_cache).stroke
        speed = stroke.speed if speed is None else speed
        aim_deg = stroke.aim_deg if aim_deg is None else aim_deg
    table, method = _table(p, method, table_cache)
    d = _core.spin_map(p._core, float(speed), float(aim_deg), int(grid), float(spin_max), int(threads), method,
                       accuracy, int(max_events), table)
    return SpinMap(p, d["speed"], d["aim_deg"], d["spin_max"], d["grid"], d["landing"], d["not_potting"],
                   d["cells"])
