"""Stroke, Shot, Trajectory, Plan, SpinMap: what the computations return."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._problem import Problem


@dataclass(frozen=True)
class Stroke:
    """A cue stroke: speed (m/s, the cue ball's just after the strike), aim_deg (the
    cue's direction, deg counter-clockwise from +x), topspin_k and sidespin_k (the
    dimensionless spins k = w R / V: 1 is natural roll, < 0 draw; sidespin > 0 right)
    and elevation_deg (the cue above the horizontal, deg; 0 a level cue)."""
    speed: float
    aim_deg: float
    topspin_k: float = 0.0
    sidespin_k: float = 0.0
    elevation_deg: float = 0.0

    def describe(self) -> str:
        """The stroke in a player's words (tip offsets)."""
        return _core.describe_stroke(self.speed, self.aim_deg, self.topspin_k, self.sidespin_k,
                                     self.elevation_deg)


StrokeLike = Union[Stroke, Mapping[str, float], Sequence[float]]


def as_stroke(stroke: StrokeLike) -> Stroke:
    if isinstance(stroke, Stroke):
        return stroke
    if isinstance(stroke, Mapping):
        return Stroke(**{k: float(v) for k, v in stroke.items()})
    values = [float(v) for v in stroke]
    if not 2 <= len(values) <= 5:
        error = _core.InputError("stroke must be (speed, aim_deg[, topspin_k[, sidespin_k[, elevation_deg]]]), "
                                 f"got {len(values)} numbers")
        error.field = "stroke"
        raise error
    return Stroke(*values)


class Trajectory(NamedTuple):
    """Every ball's position over a shot: t (s, shape (n,)), x and y (m, shape (n, balls),
    a column per ball in Shot.ball_names' order; NaN once a ball has dropped)."""
    t: np.ndarray
    x: np.ndarray
    y: np.ndarray


class Shot:
    """A simulated stroke on a problem's table: how it ended, every ball's outcome and
    events, its trajectory and a picture."""

    def __init__(self, core: "_core.ShotResult", problem: Problem) -> None:
        self._core = core
        self.problem = problem
        self.stroke = Stroke(*core.stroke)

    status = property(lambda self: self._core.status,
                      doc="How the shot ended for the cue ball: rest, pocketed, hit_obstacle, ...")
    message = property(lambda self: self._core.message, doc="Why, when the status is a failure.")
    duration = property(lambda self: self._core.duration, doc="s from the strike to the cue ball's rest.")
    final_position = property(lambda self: self._core.final_position, doc="The cue ball's final position (m).")
    cushion_hits = property(lambda self: self._core.cushion_hits, doc="The cue ball's cushion contacts.")
    ball_names = property(lambda self: self._core.ball_names, doc="Every ball, the cue ball first.")
    balls = property(lambda self: self._core.balls,
                     doc="Each ball's outcome: name, start, final_position (m), pocketed, pocket, cushion_hits.")

    @property
    def events(self) -> List[Dict[str, Any]]:
        """Every ball's events in time order: time (s), ball, type (strike, slide_to_roll,
        spin_stop, cushion, pocket, obstacle, rest, ball_contact, jaw), x, y (m), vx, vy
        (m/s, just after), spin (rad/s), cushion, index, other, normal_speed (m/s),
        impulse (N s)."""
        return self._core.events

    @property
    def verdict(self) -> Dict[str, Any]:
        """What the stroke makes of the problem: failure (none, off_target, pot_missed, ...),
        reason, solves, pot_made (None without a pot), miss_distance (m)."""
        return self._core.verdict

    @property
    def solves(self) -> bool:
        return bool(self.verdict["solves"])

    def trajectory(self, dt: float = 0.01) -> Trajectory:
        """Every ball at t = 0, dt, 2 dt, ... (s) and at each event, to the last event."""
        return Trajectory(*self._core.trajectory(float(dt)))

    def plot(self, ax: Any = None, dt: float = 0.005) -> Any:
        """Draws the table, the pockets, the target zone and every ball's path on a
        matplotlib Axes (a new figure's when None); returns the Axes. Needs matplotlib."""
        import matplotlib.pyplot as plt  # optional dependency
        from matplotlib.patches import Circle, Rectangle

        if ax is None:
            _, ax = plt.subplots(figsize=(9, 5))
        table = self.problem.table
        radius = self.problem.cue.radius
        ax.add_patch(Rectangle((0, 0), table.length, table.width, facecolor="#1f6f3f",
                               edgecolor="#4a2b12", lw=6, zorder=0))
        for p in table.pockets:
            ax.add_patch(Circle((p.x, p.y), p.radius, color="black", zorder=1))
        if self.problem.target is not None:
            ax.add_patch(Circle(self.problem.target, self.problem.tolerance, fill=False,
                                ls="--", color="yellow", zorder=2))
        for ox, oy in self.problem.obstacles:
            ax.add_patch(Circle((ox, oy), radius, color="grey", zorder=3))
        t, x, y = self.trajectory(dt)
        colours = ["white", "red", "gold", "deepskyblue", "orange", "violet", "black"]
        for b, name in enumerate(self.ball_names):
            colour = colours[b % len(colours)]
            ax.plot(x[:, b], y[:, b], color=colour, lw=1.2, zorder=4, label=name)
            start = self.balls[b]["start"]
            ax.add_patch(Circle(start, radius, fill=False, color=colour, zorder=5))
            ax.add_patch(Circle(self.balls[b]["final_position"], radius, color=colour, zorder=5))
        ax.set_xlim(-0.1, table.length + 0.1)
        ax.set_ylim(-0.1, table.width + 0.1)
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(f"{self.problem.name}: {self.stroke.speed:.3g} m/s at {self.stroke.aim_deg:.4g} deg, "
                     f"{self.status}")
        return ax

    def __repr__(self) -> str:
        return f"Shot({self.status}, final_position={self.final_position}, cushions={self.cushion_hits})"


class Plan:
    """The planner's answer: status (solved, no_solution_found, budget_exhausted,
    unreachable), the best stroke with its success numbers, the alternatives."""

    def __init__(self, result: Dict[str, Any], problem: Problem, method: str) -> None:
        self._result = result
        self.problem = problem
        self._shot: Optional[Shot] = None
        self._method = method

    status = property(lambda self: self._result["status"])
    message = property(lambda self: self._result["message"])
    best = property(lambda self: self._result["best"], doc="The best stroke and what it does (a dict).")
    alternatives = property(lambda self: self._result["alternatives"], doc="Other ways, best first.")
    evaluations = property(lambda self: self._result["evaluations"], doc="Shot simulations made.")
    time_s = property(lambda self: self._result["time_s"], doc="Wall clock (s).")

    @property
    def solved(self) -> bool:
        return self.status == "solved"

    @property
    def stroke(self) -> Stroke:
        b = self.best
        return Stroke(b["speed"], b["aim_deg"], b["topspin_k"], b["sidespin_k"], b["elevation_deg"])

    @property
    def success(self) -> Dict[str, Optional[Dict[str, float]]]:
        """Chances under a player's noise: pot, position, both, next, each
        {p, low, high, samples, successes} (95 % Wilson interval) or None."""
        return self.best["success"]

    @property
    def success_probability(self) -> float:
        return self.best["success_probability"]

    @property
    def miss_distance(self) -> float:
        """m from the target to where the best stroke stops."""
        return self.best["miss_distance"]

    @property
    def shot(self) -> Shot:
        """The best stroke simulated on the problem's table (the exact impact method,
        as the planner verifies its answer)."""
        if self._shot is None:
            from . import simulate
            self._shot = simulate(self.problem, self.stroke, method="exact")
        return self._shot

    def record(self) -> Dict[str, Any]:
        """One flat row: what solve_many returns for each problem."""
        return record_of(self._result)

    def __repr__(self) -> str:
        return f"Plan({self.status}, {self.stroke}, success={self.success_probability:.3f})"


def record_of(result: Dict[str, Any]) -> Dict[str, Any]:
    b = result["best"]
    s = b["success"]
    return {
        "name": result["name"], "status": result["status"],
        "speed": b["speed"], "aim_deg": b["aim_deg"], "topspin_k": b["topspin_k"],
        "sidespin_k": b["sidespin_k"], "elevation_deg": b["elevation_deg"],
        "success": s["both"]["p"], "p_pot": s["pot"]["p"] if s["pot"] else None,
        "p_position": s["position"]["p"],
        "miss_distance": b["miss_distance"], "final_x": b["final_position"][0],
        "final_y": b["final_position"][1], "cushion_hits": b["cushion_hits"],
        "family": b["family"], "evaluations": result["evaluations"], "time_s": result["time_s"],
        "message": result["message"],
    }


@dataclass
class SpinMap:
    """Where every spin within the miscue limit sends the cue ball for one speed (m/s)
    and aim (deg): cells holds numpy columns topspin_k, sidespin_k, final_x, final_y (m),
    miss_distance (m), cushion_hits, lands, aim_deg, pots, outcome."""
    problem: Problem
    speed: float
    aim_deg: float
    spin_max: float
    grid: int
    landing: int
    not_potting: int
    cells: Dict[str, Any]

    def plot(self, ax: Any = None) -> Any:
        """The tip-offset disc, each spin coloured by its miss distance, those that land
        outlined; returns the matplotlib Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(5, 5))
        c = self.cells
        right, up = c["sidespin_k"] / 2.5, c["topspin_k"] / 2.5  # tip offset / R
        miss = np.minimum(c["miss_distance"], 1.0)
        points = ax.scatter(right, up, c=miss, cmap="viridis_r", s=30, marker="s")
        ax.scatter(right[c["lands"]], up[c["lands"]], facecolors="none", edgecolors="red", s=40,
                   marker="s", label="lands")
        ax.set_aspect("equal")
        ax.set_xlabel("tip offset right / R")
        ax.set_ylabel("tip offset up / R")
        ax.set_title(f"{self.problem.name}: {self.landing} of {len(miss)} spins land")
        ax.figure.colorbar(points, ax=ax, label="miss distance (m, capped at 1)")
        return ax
