"""Tests of the Python package `cueplan` (python/cueplan, its extension cueplan._core).

Answers are held against the C++ libraries' own scalar paths, reached through the
command line run as a user runs it (`cueplan rebound --json`, `collide --json`,
`simulate --json`, `rebound --batch`); the trajectory against the shot's own events;
bad input against the field the typed errors name; the GIL's release against a second
Python thread that must keep running while C++ computes. Run by ctest with PYTHONPATH at
build/python and CUEPLAN_BINARY, CUEPLAN_PROBLEMS, CUEPLAN_VERSION set; exits 77
(skipped) when numpy or the package is missing.
"""
import csv
import inspect
import io
import json
import os
import pickle
import subprocess
import sys
import tempfile
import threading
import time
import unittest

try:
    import numpy as np
    import cueplan
except ImportError as missing:  # pragma: no cover - a package not installed
    print(f"skipped: {missing} (scripts/setup.sh installs python3-numpy and pybind11-dev)")
    sys.exit(77)

BINARY = os.environ.get("CUEPLAN_BINARY")  # absent when the command line is not built
PROBLEMS = os.environ["CUEPLAN_PROBLEMS"]
ONE_RAIL = os.path.join(PROBLEMS, "one_rail_position.yaml")
POT = os.path.join(PROBLEMS, "pots", "straight_pot_corner.yaml")
# A quick search that the evaluation budget ends, so the answer is reproducible.
QUICK = dict(method="exact", max_evaluations=300, samples=20, alternatives=2, max_time=120, seed=3)


def command_line(*args, stdin=None):
    if not BINARY:
        raise unittest.SkipTest("the command line is not built")
    run = subprocess.run([BINARY, *map(str, args)], capture_output=True, text=True, input=stdin)
    assert run.returncode in (0, 1), run.stderr
    return run.stdout


class Signatures(unittest.TestCase):
    def test_parameters_and_defaults_are_real(self):
        sig = inspect.signature(cueplan.rebound)
        self.assertEqual(list(sig.parameters)[:4], ["speed", "angle", "topspin_k", "sidespin_k"])
        self.assertEqual(sig.parameters["topspin_k"].default, 1.0)
        self.assertEqual(sig.parameters["mu_cushion"].default, 0.14)
        self.assertEqual(sig.parameters["method"].kind, inspect.Parameter.KEYWORD_ONLY)
        self.assertEqual(list(inspect.signature(cueplan.collide).parameters)[:4],
                         ["speed", "cut", "topspin_k", "sidespin_k"])
        solve = inspect.signature(cueplan.solve).parameters
        for name, default in (("seed", 1), ("max_evaluations", 2000), ("max_time", 10.0), ("samples", 200),
                              ("method", "table"), ("threads", 1)):
            self.assertEqual(solve[name].default, default, name)
        self.assertIn("threads", inspect.signature(cueplan.solve_many).parameters)
        self.assertEqual(list(inspect.signature(cueplan.simulate).parameters)[:2], ["problem", "stroke"])
        self.assertEqual(list(inspect.signature(cueplan.Shot.trajectory).parameters), ["self", "dt"])
        self.assertEqual(list(inspect.signature(cueplan.Stroke).parameters),
                         ["speed", "aim_deg", "topspin_k", "sidespin_k", "elevation_deg"])

    def test_docstrings_give_units(self):
        for f, units in ((cueplan.rebound, ["m/s", "deg", "rad/s"]), (cueplan.collide, ["m/s", "deg"]),
                         (cueplan.simulate, ["m/s", "deg"]), (cueplan.solve, ["(s)"]),
                         (cueplan.Stroke, ["m/s", "deg"])):
            for unit in units:
                self.assertIn(unit, f.__doc__, f.__name__)

    def test_version_is_the_projects(self):
        self.assertEqual(cueplan.__version__, os.environ["CUEPLAN_VERSION"])

    def test_stubs_and_marker_ship_with_the_package(self):
        here = os.path.dirname(cueplan.__file__)
        self.assertTrue(os.path.exists(os.path.join(here, "py.typed")))
        with open(os.path.join(here, "_core.pyi")) as f:
            stubs = f.read()
        for name in ("def rebound", "def collide", "def simulate", "def plan", "def plan_many", "class Problem",
                     "class InputError(ValueError)"):
            self.assertIn(name, stubs)


class ReboundAndCollide(unittest.TestCase):
    def test_rebound_is_the_scalar_result(self):
        for speed, angle, kt, ks in ((1.3, 37.5, 1.0, 0.0), (2.0, 90.0, -0.5, 0.7), (0.4, 150.0, 2.0, -1.0)):
            expected = json.loads(command_line("rebound", "--speed", speed, "--angle", angle, "--topspin-k", kt,
                                               "--sidespin-k", ks, "--json"))
            got = cueplan.rebound(speed, angle, kt, ks)
            self.assertEqual(got["rebound_speed"], expected["rebound_speed"])
            self.assertEqual(got["rebound_angle_deg"], expected["rebound_angle_deg"])
            self.assertEqual([got["vx"], got["vy"]], expected["velocity"])
            self.assertEqual([got["wx"], got["wy"], got["wz"]], expected["spin"])
            self.assertEqual(got["status"], expected["status"])
        paper = json.loads(command_line("rebound", "--speed", 1, "--angle", 45, "--method", "paper", "--steps", 200,
                                        "--mu-cushion", 0.2, "--json"))
        got = cueplan.rebound(1, 45, method="paper", steps=200, mu_cushion=0.2)
        self.assertEqual(got["rebound_angle_deg"], paper["rebound_angle_deg"])

    def test_rebound_arrays_are_the_batch_rows(self):
        rng = np.random.default_rng(7)
        n = 600
        rows = np.column_stack([rng.uniform(0.3, 3, n), rng.uniform(5, 175, n), rng.uniform(-1.5, 2, n),
                                rng.uniform(-1.5, 1.5, n)])
        text = "speed,angle_deg,topspin_k,sidespin_k\n" + "".join(",".join(repr(float(x)) for x in r) + "\n"
                                                                 for r in rows)
        table = list(csv.DictReader(io.StringIO(command_line("rebound", "--batch", "-", stdin=text))))
        got = cueplan.rebound(rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3], threads=2)
        self.assertEqual(got["rebound_speed"].shape, (n,))
        for key in ("rebound_speed", "rebound_angle_deg", "vx", "vy", "wx", "wy", "wz"):
            np.testing.assert_array_equal(got[key], [float(r[key]) for r in table], key)
        self.assertEqual(list(got["status"]), [r["status"] for r in table])
        # Broadcasting: a grid of angles against one speed keeps its shape.
        grid = cueplan.rebound(1.0, np.linspace(10, 170, 12).reshape(3, 4))
        self.assertEqual(grid["rebound_speed"].shape, (3, 4))
        self.assertEqual(grid["rebound_speed"][1, 2], cueplan.rebound(1.0, float(np.linspace(10, 170, 12)[6]))["rebound_speed"])

    def test_collide_is_the_scalar_result(self):
        for speed, cut, kt, ks in ((1.0, 30.0, 1.0, 0.0), (2.0, -15.0, -0.4, 0.6)):
            expected = json.loads(command_line("collide", "--speed", speed, "--cut", cut, "--topspin-k", kt,
                                               "--sidespin-k", ks, "--json"))
            got = cueplan.collide(np.array([speed, speed]), cut, kt, ks)
            for i in range(2):
                self.assertEqual([got["cue_vx"][i], got["cue_vy"][i]], expected["cue_ball"]["velocity"])
                self.assertEqual([got["object_wx"][i], got["object_wy"][i], got["object_wz"][i]],
                                 expected["object_ball"]["spin"])
                self.assertEqual(got["object_rolling_angle_deg"][i], expected["object_ball"]["rolling_angle_deg"])
                self.assertEqual(got["throw_deg"][i], expected["throw_deg"])


class Problems(unittest.TestCase):
    def test_defaults_are_resolved_and_readable(self):
        p = cueplan.Problem(ONE_RAIL)
        self.assertEqual(p.cue_ball, (0.9, 1.2))
        self.assertEqual(p.target, (2.2, 1.1))
        self.assertEqual(p.table.length, 3.569)
        self.assertEqual(len(p.table.pockets), 6)
        self.assertEqual(p.cue.radius, 0.02625)
        self.assertEqual(p.physics["mu_roll"], 0.01)
        self.assertEqual(p.limits["speed"], (0.2, 4.5))
        pot = cueplan.Problem(POT)
        self.assertEqual(pot.pot["ball"], pot.balls[0].name)
        self.assertIsNone(cueplan.Problem({"cue_ball": [0.5, 0.5], "pot": {"ball": "red", "pocket": "top_left"},
                                           "balls": {"red": [0.3, 1.4]}}).target)

    def test_text_dict_and_file_agree(self):
        with open(ONE_RAIL) as f:
            text = f.read()
        a, b = cueplan.Problem(ONE_RAIL), cueplan.Problem.from_text(text)
        c = cueplan.Problem({"cue_ball": [0.9, 1.2], "target": [2.2, 1.1]})
        for p in (b, c):
            self.assertEqual(p.cue_ball, a.cue_ball)
            self.assertEqual(p.target, a.target)
        again = pickle.loads(pickle.dumps(a.with_positions(cue_ball=(1.0, 0.5))))
        self.assertEqual(again.cue_ball, (1.0, 0.5))
        self.assertEqual(again.name, a.name)


class BadInputRaisesNamingTheField(unittest.TestCase):
    def assert_field(self, field, call, *args, **kwargs):
        with self.assertRaises(cueplan.InputError) as caught:
            call(*args, **kwargs)
        self.assertIsInstance(caught.exception, ValueError)
        self.assertEqual(caught.exception.field, field, str(caught.exception))
        return str(caught.exception)

    def test_rebound_and_collide(self):
        self.assertIn("(0, 180)", self.assert_field("angle", cueplan.rebound, 1, 190))
        self.assertIn("angle[2]", self.assert_field("angle", cueplan.rebound, 1, np.array([10, 20, 0.0])))
        self.assert_field("speed", cueplan.rebound, -1, 45)
        self.assert_field("mu_cushion", cueplan.rebound, 1, 45, mu_cushion=-1)
        self.assert_field("restitution", cueplan.rebound, 1, 45, restitution=1.5)
        self.assert_field("steps", cueplan.rebound, 1, 45, method="paper", steps=0)
        self.assert_field("method", cueplan.rebound, 1, 45, method="guess")
        self.assert_field("cut", cueplan.collide, 1, 95)
        self.assert_field("mu_ball", cueplan.collide, 1, 10, mu_ball=-0.1)

    def test_problems_strokes_and_options(self):
        self.assert_field("table.length", cueplan.Problem,
                          {"cue_ball": [0.9, 1.2], "target": [2.2, 1.1], "table": {"length": -1}})
        self.assert_field("cue_ball", cueplan.Problem, {"cue_ball": [0.5], "target": [1, 1]})
        self.assert_field("cue_ball", cueplan.Problem(ONE_RAIL).with_positions, cue_ball=(9.0, 0.5))
        self.assert_field("stroke.speed", cueplan.simulate, ONE_RAIL, (-1, 0))
        self.assert_field("stroke", cueplan.simulate, ONE_RAIL, (1.0,))
        self.assertIsNone(cueplan.InputError("raised from Python").field)
        self.assert_field("dt", cueplan.simulate(ONE_RAIL, (1, 0)).trajectory, 0)
        self.assert_field("max_time", cueplan.solve, ONE_RAIL, max_time=-1)
        self.assert_field("max_evaluations", cueplan.solve, ONE_RAIL, max_evaluations=0)
        self.assert_field("global_method", cueplan.solve, ONE_RAIL, global_method="best")
        self.assert_field("accuracy", cueplan.solve, ONE_RAIL, accuracy=2)
        self.assert_field("grid", cueplan.spin_map, ONE_RAIL, 1.0, 0.0, grid=1, method="exact")


class Simulate(unittest.TestCase):
    def test_the_command_lines_outcome(self):
        expected = json.loads(command_line("simulate", POT, "--speed", 1.5, "--aim", 200, "--topspin-k", 0.2,
                                           "--method", "exact", "--json"))
        shot = cueplan.simulate(POT, cueplan.Stroke(1.5, 200.0, 0.2))
        self.assertEqual(list(shot.final_position), expected["final_position"])
        self.assertEqual(shot.status, expected["status"])
        self.assertEqual(shot.cushion_hits, expected["cushion_hits"])

    def test_trajectory_passes_through_every_event(self):
        shot = cueplan.simulate(POT, {"speed": 1.8, "aim_deg": 225.0, "topspin_k": -0.3})
        t, x, y = shot.trajectory(0.01)
        self.assertEqual(x.shape, (len(t), len(shot.ball_names)))
        self.assertTrue(np.all(np.diff(t) > 0))
        events = shot.events
        self.assertGreater(len(events), 4)
        self.assertIn("ball_contact", {e["type"] for e in events})
        for e in events:
            b = shot.ball_names.index(e["ball"])
            i = int(np.searchsorted(t, e["time"]))
            self.assertEqual(t[i], e["time"])
            self.assertAlmostEqual(x[i, b], e["x"], delta=1e-9, msg=e)
            self.assertAlmostEqual(y[i, b], e["y"], delta=1e-9, msg=e)
        for b, ball in enumerate(shot.balls):
            if ball["pocketed"]:
                self.assertTrue(np.isnan(x[-1, b]))
            else:
                self.assertAlmostEqual(x[-1, b], ball["final_position"][0], delta=1e-9)
        # Between events the samples lie dt apart.
        self.assertTrue(np.all(np.diff(t) <= 0.01 + 1e-12))

    def test_plot_draws_every_ball(self):
        try:
            import matplotlib
        except ImportError:
            self.skipTest("matplotlib missing")
        matplotlib.use("Agg")
        shot = cueplan.simulate(POT, (1.8, 225.0, -0.3))
        ax = shot.plot()
        self.assertEqual(len(ax.lines), len(shot.ball_names))


class Solve(unittest.TestCase):
    def test_a_shipped_pot_is_solved_and_pots(self):
        # 800 simulations: at QUICK's 300 the search's seed-independent half (issue 31)
        # misses this pot's zone whatever the seed (bench/README, "Stable answers").
        plan = cueplan.solve(POT, **dict(QUICK, max_evaluations=800))
        self.assertEqual(plan.status, "solved", plan.message)
        self.assertGreater(plan.success["pot"]["p"], 0)
        shot = plan.shot
        self.assertTrue(shot.verdict["pot_made"], shot.verdict)
        red = next(b for b in shot.balls if b["name"] == cueplan.Problem(POT).pot["ball"])
        self.assertTrue(red["pocketed"])
        self.assertEqual(red["pocket"], cueplan.Problem(POT).pot["pocket"])

    def test_the_command_lines_answer(self):
        args = []
        for k, v in QUICK.items():
            args += ["--" + k.replace("_", "-"), v]
        expected = json.loads(command_line("solve", ONE_RAIL, "--json", "--threads", 1, *args))
        plan = cueplan.solve(ONE_RAIL, **QUICK)
        self.assertEqual(plan.status, expected["status"])
        stroke = expected["shot"]
        self.assertEqual((plan.stroke.speed, plan.stroke.aim_deg, plan.stroke.topspin_k),
                         (stroke["speed"], stroke["aim_deg"], stroke["topspin_k"]))
        self.assertEqual(plan.success["both"]["p"], expected["success"]["both"]["p"])
        self.assertEqual(plan.best["stroke_words"], expected["stroke"])

    def test_solve_many_gives_records_in_order(self):
        paths = [ONE_RAIL, POT, os.path.join(PROBLEMS, "pots", "long_pot.yaml")]
        options = dict(QUICK, alternatives=0)
        records = cueplan.solve_many(paths, threads=2, **options)
        self.assertEqual([r["name"] for r in records], [cueplan.Problem(p).name for p in paths])
        for path, record in zip(paths, records):
            alone = cueplan.solve(path, **options).record()
            self.assertEqual({k: v for k, v in record.items() if k != "time_s"},
                             {k: v for k, v in alone.items() if k != "time_s"})
        try:
            import pandas
        except ImportError:
            return  # pandas is optional; the records are plain dicts either way
        frame = pandas.DataFrame(records)
        self.assertEqual(list(frame["name"]), [r["name"] for r in records])

    def test_solve_many_with_the_table_and_a_closed_form_cushion(self):
        """The default method (the impact table) for a Mathavan cushion, none needed for
        Han's closed form: each problem gets its own."""
        han = {"cue_ball": [0.9, 1.2], "target": [2.2, 1.1], "limits": {"cushions": 1},
               "physics": {"cushion_model": "han_2005"}}
        # 600 simulations: one_rail_position is solved from 350 up (300 is on the edge: whether
        # the search lands within it depends on rounding in its path).
        records = cueplan.solve_many([ONE_RAIL, han], threads=2, max_evaluations=600, samples=0, max_time=120)
        self.assertEqual([r["status"] for r in records], ["solved", "solved"], records)

    def test_spin_map_cells(self):
        m = cueplan.spin_map(ONE_RAIL, 1.002, -60.36, grid=11, method="exact")
        n = len(m.cells["topspin_k"])
        self.assertGreater(n, 50)
        self.assertEqual(int(m.cells["lands"].sum()), m.landing)
        self.assertTrue(np.all(np.hypot(m.cells["topspin_k"], m.cells["sidespin_k"]) <= m.spin_max + 1e-12))


class GilIsReleased(unittest.TestCase):
    def test_python_runs_while_cpp_computes(self):
        """A Python thread counts while another thread is inside a long solve: with the
        GIL held through the solve it could not count at all."""
        done = threading.Event()
        spent = {}

        def long_solve():
            started = time.perf_counter()
            cueplan.solve(ONE_RAIL, method="exact", max_evaluations=8000, samples=50, max_time=120)
            spent["solve"] = time.perf_counter() - started
            done.set()

        worker = threading.Thread(target=long_solve)
        worker.start()
        time.sleep(0.05)
        counted = 0
        while not done.is_set():
            counted += 1
        worker.join()
        self.assertGreater(counted / spent["solve"], 2000, f"counted {counted} in {spent['solve']:.3f} s")
        self.assertGreater(spent["solve"], 0.1, "the solve was too short to tell")

    def test_rebound_releases_it_too(self):
        rows = np.full(200000, 1.0)
        done = threading.Event()
        counted = [0]

        def count():
            while not done.is_set():
                counted[0] += 1

        counter = threading.Thread(target=count)
        counter.start()
        started = time.perf_counter()
        cueplan.rebound(rows, np.linspace(5, 175, rows.size), threads=1)
        spent = time.perf_counter() - started
        done.set()
        counter.join()
        self.assertGreater(counted[0] / spent, 2000, f"counted {counted[0]} in {spent:.3f} s")


if __name__ == "__main__":
    unittest.main(verbosity=2)
