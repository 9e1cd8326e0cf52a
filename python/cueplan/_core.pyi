# Stubs of cueplan._core, the C++ extension (python/src/). The package cueplan wraps it
# with defaults and docstrings; units are SI (m, kg, s, m/s, rad/s), angles in degrees.
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

Column = npt.NDArray[np.float64]

class InputError(ValueError):
    field: Optional[str]

IMPACT_STATUS: Tuple[str, ...]
COLLISION_STATUS: Tuple[str, ...]

class CushionParams:
    def __init__(self, mass: float, radius: float, cushion_height: Optional[float], mu_cushion: float,
                 mu_table: float, restitution: float, rigid_speed_limit: float, model: str) -> None: ...
    mass: float
    radius: float
    cushion_height: float
    mu_cushion: float
    mu_table: float
    restitution: float
    rigid_speed_limit: float
    model: str

class BallBallParams:
    def __init__(self, mass: float, radius: float, mu_ball: float, restitution: float, mu_table: float,
                 model: str, friction: str) -> None: ...

class ImpactTable:
    file: str
    measured_error: Dict[str, float]

def load_or_build_table(params: CushionParams, cache_dir: str, threads: int = 0) -> ImpactTable: ...
def rebound(speed: Column, angle: Column, topspin_k: Column, sidespin_k: Column, params: CushionParams,
            method: str, tolerance: float, steps: int, max_steps: int, lanes: int, threads: int,
            table: Optional[ImpactTable], scalar: bool) -> Dict[str, np.ndarray]: ...
def collide(speed: Column, cut: Column, topspin_k: Column, sidespin_k: Column, params: BallBallParams,
            method: str, tolerance: float, steps: int, max_steps: int, threads: int,
            scalar: bool) -> Dict[str, np.ndarray]: ...

class Problem:
    name: str
    source: str
    table: Dict[str, Any]
    physics: Dict[str, Any]
    limits: Dict[str, Any]
    ball: Dict[str, float]
    cue_ball: Tuple[float, float]
    target: Optional[Tuple[float, float]]
    tolerance: float
    balls: List[Tuple[str, float, float]]
    obstacles: List[Tuple[float, float]]
    pot: Optional[Dict[str, str]]
    first_contact: Optional[str]
    next: List[Dict[str, str]]
    cushion_params: CushionParams
    def describe(self) -> str: ...
    def with_positions(self, cue_ball: Optional[Tuple[float, float]],
                       target: Optional[Tuple[float, float]]) -> Problem: ...

def load_problem(path: str) -> Problem: ...
def parse_problem(text: str, source: str) -> Problem: ...

class ShotResult:
    status: str
    message: str
    duration: float
    final_position: Tuple[float, float]
    cushion_hits: int
    impact_method: str
    stroke: Tuple[float, float, float, float, float]
    ball_names: List[str]
    balls: List[Dict[str, Any]]
    events: List[Dict[str, Any]]
    verdict: Dict[str, Any]
    def trajectory(self, dt: float) -> Tuple[Column, Column, Column]: ...

def simulate(problem: Problem, speed: float, aim_deg: float, topspin_k: float, sidespin_k: float,
             elevation_deg: float, method: str, accuracy: Optional[float], max_events: int,
             table: Optional[ImpactTable]) -> ShotResult: ...
def describe_stroke(speed: float, aim_deg: float, topspin_k: float, sidespin_k: float,
                    elevation_deg: float) -> str: ...

class PlannerOptions: ...

def planner_options(seed: int, max_evaluations: int, max_time: float, starts: int, samples: int, noise: float,
                    robust: bool, alternatives: int, global_method: str, local_method: str,
                    enforce_rigid_limit: bool, threads: int) -> PlannerOptions: ...
def plan(problem: Problem, options: PlannerOptions, method: str, accuracy: Optional[float], max_events: int,
         table: Optional[ImpactTable]) -> Dict[str, Any]: ...
def plan_many(problems: Sequence[Problem], options: PlannerOptions, methods: Sequence[str], accuracy: Optional[float],
              max_events: int, tables: Sequence[Optional[ImpactTable]], threads: int) -> List[Dict[str, Any]]: ...
def spin_map(problem: Problem, speed: float, aim_deg: float, grid: int, spin_max: float, threads: int,
             method: str, accuracy: Optional[float], max_events: int,
             table: Optional[ImpactTable]) -> Dict[str, Any]: ...
