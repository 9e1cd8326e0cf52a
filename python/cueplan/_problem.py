"""Problem, Table, Ball, Pocket: a shot-planning problem as the problems library loads it,
every default resolved and readable."""
from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _core

Point = Tuple[float, float]


@dataclass(frozen=True)
class Pocket:
    """A pocket: its name in problem files, centre (m; the mouth's middle for a jawed
    pocket) and capture radius (m; half the mouth for a jawed pocket)."""
    name: str
    x: float
    y: float
    radius: float
    jawed: bool = False


@dataclass(frozen=True)
class Table:
    """The table: the playing area between the cushion noses, length along x and width
    along y (m), the cushion's contact height above the cloth (m), and the pockets."""
    length: float
    width: float
    cushion_height: float
    pockets: Tuple[Pocket, ...] = ()


@dataclass(frozen=True)
class Ball:
    """A ball at rest: its name ("cue" for the cue ball), centre (m, table frame),
    radius (m) and mass (kg)."""
    name: str
    x: float
    y: float
    radius: float
    mass: float

    @property
    def position(self) -> Point:
        return (self.x, self.y)


ProblemLike = Union["Problem", str, "os.PathLike[str]", Mapping[str, Any]]


class Problem:
    """A shot-planning problem: the table and its physics, the balls, the target and the
    planner's limits, loaded and checked by the C++ problems library (problems/README.md
    is the format).

    ``Problem(source)`` takes a problem file's path (YAML or JSON), the text of one, or a
    dict of its fields; bad input raises :class:`cueplan.InputError` whose ``field`` is
    the file's field name (``table.length``, ``cue_ball``, ``limits.speed[1]``).
    """

    def __init__(self, source: Union[str, "os.PathLike[str]", Mapping[str, Any]], *,
                 name: Optional[str] = None) -> None:
        if isinstance(source, Mapping):
            text = json.dumps(source)
            self._init(_core.parse_problem(text, name or "<dict>"), ("text", text, name or "<dict>"))
        elif isinstance(source, (str, os.PathLike)):
            s = os.fspath(source)
            if isinstance(source, os.PathLike) or ("\n" not in s and not s.lstrip().startswith("{")
                                                   and (os.path.exists(s) or ":" not in s)):
                self._init(_core.load_problem(s), ("file", s, _read(s)))
            else:
                self._init(_core.parse_problem(s, name or "<string>"), ("text", s, name or "<string>"))
        else:
            raise TypeError(f"a problem is a file's path, its text or a dict of its fields, "
                            f"not {type(source).__name__}")

    def _init(self, core: "_core.Problem", origin: Tuple, moves: Tuple = ()) -> None:
        self._core = core
        self._origin = origin
        self._moves = moves

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Problem":
        """Loads a problem file (YAML or JSON)."""
        p = cls.__new__(cls)
        s = os.fspath(path)
        p._init(_core.load_problem(s), ("file", s, _read(s)))
        return p

    @classmethod
    def from_text(cls, text: str, source: str = "<string>") -> "Problem":
        """Parses a problem from YAML or JSON text; ``source`` names it in messages."""
        p = cls.__new__(cls)
        p._init(_core.parse_problem(text, source), ("text", text, source))
        return p

    @classmethod
    def from_dict(cls, fields: Mapping[str, Any], source: str = "<dict>") -> "Problem":
        """A problem from a dict of a problem file's fields."""
        return cls.from_text(json.dumps(fields), source)

    # Pickled as its text and the moves made since (for Dask and multiprocessing).
    def __reduce__(self):
        return (_rebuild, (self._origin, self._moves))

    @property
    def name(self) -> str:
        """The file's ``name``, or the stem of its file name."""
        return self._core.name

    @property
    def source(self) -> str:
        """The file's path, or the source name given with the text."""
        return self._core.source

    @property
    def table(self) -> Table:
        t = self._core.table
        return Table(t["length"], t["width"], t["cushion_height"],
                     tuple(Pocket(**p) for p in t["pockets"]))

    @property
    def cue_ball(self) -> Point:
        """Where the cue ball lies (m)."""
        return self._core.cue_ball

    @property
    def target(self) -> Optional[Point]:
        """Where the cue ball should come to rest (m); None for a pure pot or an escape."""
        return self._core.target

    @property
    def tolerance(self) -> float:
        """Radius of the landing zone around the target (m)."""
        return self._core.tolerance

    @property
    def cue(self) -> Ball:
        """The cue ball where it lies."""
        b = self._core.ball
        return Ball("cue", *self.cue_ball, b["radius"], b["mass"])

    @property
    def balls(self) -> List[Ball]:
        """The object balls, as the file names them."""
        b = self._core.ball
        return [Ball(n, x, y, b["radius"], b["mass"]) for n, x, y in self._core.balls]

    @property
    def obstacles(self) -> List[Point]:
        """Balls nothing may touch (m)."""
        return self._core.obstacles

    @property
    def physics(self) -> Dict[str, Any]:
        """Cloth, cushion and ball constants: mu_slide, mu_roll, mu_spin, gravity (m/s^2),
        mu_cushion, restitution, cushion_height (m), cushion_model, mu_ball,
        ball_restitution, ball_model, ball_friction, cue_end_mass (kg)."""
        return self._core.physics

    @property
    def limits(self) -> Dict[str, Any]:
        """The planner's search space: speed (m/s), spin, aim_deg, cushions,
        elevation_deg, cushions_before_contact, object_cushions."""
        return self._core.limits

    @property
    def pot(self) -> Optional[Dict[str, str]]:
        """The pot to make ({"ball", "pocket"}), or None."""
        return self._core.pot

    @property
    def first_contact(self) -> Optional[str]:
        """The ball (or class of balls) the cue ball must strike first, or None."""
        return self._core.first_contact

    def with_positions(self, cue_ball: Optional[Sequence[float]] = None,
                       target: Optional[Sequence[float]] = None) -> "Problem":
        """A copy with the cue ball and/or the target moved (m), checked again."""
        cue = None if cue_ball is None else (float(cue_ball[0]), float(cue_ball[1]))
        tgt = None if target is None else (float(target[0]), float(target[1]))
        p = Problem.__new__(Problem)
        p._init(self._core.with_positions(cue, tgt), self._origin, self._moves + ((cue, tgt),))
        return p

    def describe(self) -> str:
        """A few lines for people: table, ball, positions, tolerance and limits."""
        return self._core.describe()

    def __repr__(self) -> str:
        return f"Problem({self.name!r}, cue_ball={self.cue_ball}, target={self.target})"


def _read(path: str) -> Optional[str]:
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except OSError:
        return None


def _rebuild(origin: Tuple, moves: Tuple) -> Problem:
    p = Problem.__new__(Problem)
    kind = origin[0]
    if kind == "file":
        path, text = origin[1], origin[2]
        core = _core.load_problem(path) if text is None or os.path.exists(path) else \
            _core.parse_problem(text, path)
    else:
        core = _core.parse_problem(origin[1], origin[2])
    p._init(core, origin)
    for cue, tgt in moves:
        p = p.with_positions(cue, tgt)
    return p


def as_problem(problem: ProblemLike) -> Problem:
    return problem if isinstance(problem, Problem) else Problem(problem)
