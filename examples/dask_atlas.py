#!/usr/bin/env python3
"""A position atlas with dask.distributed: for every cue-ball cell of a grid on the
table and one or more targets, solve the problem and record whether it was solved,
its success under a player's noise and the stroke - and draw the atlas.

Dask schedules, cueplan computes: each task is one `cueplan.solve` (the Python package,
python/), whose answer depends only on its problem and options (the evaluation budget,
not the clock, ends each search), so the atlas is the same on one machine or many.

  PYTHONPATH=build/python python3 examples/dask_atlas.py --out atlas.png
  python3 examples/dask_atlas.py --scheduler tcp://10.0.0.5:8786 --out atlas.png
  python3 examples/dask_atlas.py --serial --json atlas.json   # no Dask: the reference

Without --scheduler a LocalCluster of --workers processes (one thread each) runs on
this machine. Remote workers need the cueplan package installed (`pip install .`) or on
their PYTHONPATH; a cueplan.Problem travels to them as its file's text.

Results stream: at most --window tasks are in flight, and each record is written to
--json and folded into the picture's grid as it comes, in the order of the cells, so
memory does not grow with the atlas.
"""
import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def import_cueplan():
    """The module from PYTHONPATH, else from this checkout's build/python (and the
    workers this process starts inherit that path)."""
    try:
        import cueplan  # noqa: F401
    except ImportError:
        build = os.path.join(ROOT, "build", "python")
        sys.path.insert(0, build)
        os.environ["PYTHONPATH"] = os.pathsep.join(
            p for p in (build, os.environ.get("PYTHONPATH")) if p)
    import cueplan
    return cueplan


def cells_of(problem, grid):
    """Cell centres (m) of an nx-by-ny grid over the playing area inside the cushions,
    kept a ball radius and a little more from them."""
    length, width = problem.table.length, problem.table.width
    margin = 0.06
    nx, ny = grid
    xs = [margin + (length - 2 * margin) * (i + 0.5) / nx for i in range(nx)]
    ys = [margin + (width - 2 * margin) * (j + 0.5) / ny for j in range(ny)]
    return [(i, j, x, y) for j, y in enumerate(ys) for i, x in enumerate(xs)]


def solve_cell(problem, target, cell, options):
    """One task: the problem with the cue ball at the cell's centre, solved. Returns a
    plain dict (what the atlas records), the same wherever it runs."""
    import cueplan  # on a worker: imported there
    i, j, x, y = cell
    record = {"cell": [i, j], "cue_ball": [x, y], "target": list(target)}
    try:
        moved = problem.with_positions(cue_ball=(x, y), target=target)
        plan = cueplan.solve(moved, **options)
    except cueplan.InputError as bad:  # a cue ball in a pocket's mouth, on an obstacle, ...
        return dict(record, status="invalid_input", error=str(bad), field=bad.field)
    s = plan.stroke
    return dict(record, status=plan.status, success=plan.success["both"]["p"],
                miss_distance=plan.miss_distance,
                shot={"speed": s.speed, "aim_deg": s.aim_deg, "topspin_k": s.topspin_k,
                      "sidespin_k": s.sidespin_k, "elevation_deg": s.elevation_deg},
                stroke=plan.best["stroke_words"])


def atlas(problem, targets, grid, options, client=None, window=None):
    """Every (target, cell) solved - by the Dask client's workers, or here in turn -
    yielded one record at a time in the order of the cells, as they come: at most
    `window` tasks are in flight (four a worker by default), so neither this process
    nor the cluster holds the atlas, whatever its size."""
    jobs = ((t, c) for t in targets for c in cells_of(problem, grid))
    if client is None:
        for t, c in jobs:
            yield solve_cell(problem, t, c, options)
        return
    from collections import deque
    if window is None:
        window = 4 * max(1, len(client.scheduler_info()["workers"]))
    # Scatter the problem once; one task a cell. The oldest task's record is handed on
    # as soon as it is done, and another task takes its place, so the workers stay busy
    # while this process waits in order.
    shared = client.scatter(problem, broadcast=True)
    in_flight = deque()
    for t, c in jobs:
        in_flight.append(client.submit(solve_cell, shared, t, c, options, pure=False))
        if len(in_flight) >= window:
            future = in_flight.popleft()
            yield future.result()
            future.release()
    while in_flight:
        future = in_flight.popleft()
        yield future.result()
        future.release()


class AtlasSummary:
    """What the picture and the summary line need of the records: one success value a
    cell and target, kept as each record streams past (the records are not held)."""

    def __init__(self, targets, grid):
        import math
        nx, ny = grid
        self.grid = grid
        self.targets = [list(t) for t in targets]
        # success[target][j][i]: NaN where there is no problem, 0 where none was solved.
        self.success = [[[math.nan] * nx for _ in range(ny)] for _ in targets]
        self.unsolved = [[[False] * nx for _ in range(ny)] for _ in targets]
        self.solved_by_target = [0 for _ in targets]
        self.cells = 0
        self.solved = 0

    def add(self, record):
        self.cells += 1
        t = self.targets.index(list(record["target"]))
        i, j = record["cell"]
        if record["status"] == "solved":
            self.success[t][j][i] = record["success"]
            self.solved += 1
            self.solved_by_target[t] += 1
        elif record["status"] != "invalid_input":
            self.unsolved[t][j][i] = True
            self.success[t][j][i] = 0.0


class JsonAtlasWriter:
    """The atlas as one JSON object, {"grid", "targets", "options", "records": [...]},
    written a record at a time."""

    def __init__(self, path, grid, targets, options):
        self.file = open(path, "w")
        head = json.dumps({"grid": grid, "targets": targets, "options": options})
        self.file.write(head[:-1] + ', "records": [')
        self.first = True

    def add(self, record):
        self.file.write(("" if self.first else ", ") + json.dumps(record))
        self.first = False

    def close(self):
        self.file.write("]}\n")
        self.file.close()


def draw(problem, targets, grid, summary, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors
    import numpy as np

    length, width = problem.table.length, problem.table.width
    nx, ny = grid
    fig, axes = plt.subplots(len(targets), 1, figsize=(9, 4.6 * len(targets)), squeeze=False)
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("#bbbbbb")
    # One colour scale for every target, so their panels compare.
    best = float(np.nanmax(np.array(summary.success, dtype=float), initial=0.0)) or 1.0
    norm = colors.Normalize(0, max(0.05, best))
    for t, (axis, target) in enumerate(zip(axes[:, 0], targets)):
        success = np.array(summary.success[t], dtype=float)
        unsolved = np.array(summary.unsolved[t], dtype=bool)
        margin = 0.06
        extent = (margin, length - margin, margin, width - margin)
        image = axis.imshow(np.ma.masked_invalid(success), origin="lower", extent=extent, cmap=cmap,
                            norm=norm,
                            interpolation="nearest")
        for j in range(ny):
            for i in range(nx):
                if unsolved[j, i]:
                    x = margin + (length - 2 * margin) * (i + 0.5) / nx
                    y = margin + (width - 2 * margin) * (j + 0.5) / ny
                    axis.plot(x, y, "x", color="white", markersize=5)
        axis.add_patch(plt.Rectangle((0, 0), length, width, fill=False, lw=2, color="#3b2410"))
        for px, py in [(0, 0), (length / 2, 0), (length, 0), (0, width), (length / 2, width), (length, width)]:
            axis.add_patch(plt.Circle((px, py), 0.045, color="black"))
        axis.plot(*target, marker="*", color="#ff3030", markersize=16, markeredgecolor="white")
        axis.set_xlim(-0.08, length + 0.08)
        axis.set_ylim(-0.08, width + 0.08)
        axis.set_aspect("equal")
        axis.set_xlabel("x (m)")
        axis.set_ylabel("y (m)")
        solved = summary.solved_by_target[t]
        axis.set_title(f"Target ({target[0]:.2f}, {target[1]:.2f}) m: {solved} of {nx * ny} cue-ball cells solved")
        fig.colorbar(image, ax=axis, label="success under a player's noise (fraction)", shrink=0.85)
    fig.suptitle("Position atlas: where the cue ball can be left on the target from each cell\n"
                 "(grey: no problem there; x: no stroke found)", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
    p.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (2)")
    p.add_argument("--serial", action="store_true", help="no Dask: solve every cell here, in turn")
    p.add_argument("--problem", default=os.path.join(ROOT, "problems", "one_rail_position.yaml"),
                   help="problem file whose table, limits and physics the atlas uses")
    p.add_argument("--target", action="append", type=lambda s: [float(v) for v in s.split(",")],
                   help="target X,Y (m); repeat for several (default: the problem's)")
    p.add_argument("--grid", nargs=2, type=int, default=[12, 6], metavar=("NX", "NY"),
                   help="cue-ball cells along the length and the width (12 6)")
    p.add_argument("--max-evaluations", type=int, default=600)
    p.add_argument("--samples", type=int, default=50)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--method", default="table", help="cushion impacts: table (fast) or exact")
    p.add_argument("--out", help="the atlas as a picture (PNG, SVG or PDF)")
    p.add_argument("--json", help="the atlas's records as JSON, written as they come")
    p.add_argument("--window", type=int,
                   help="most tasks in flight at once (default: four a worker); memory is "
                        "bounded by it, not by the atlas's size")
    return p.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    cueplan = import_cueplan()
    problem = cueplan.Problem(args.problem)
    targets = args.target or [list(problem.target)]
    # The evaluation budget, never the clock, ends each search: the atlas is reproducible.
    options = dict(method=args.method, max_evaluations=args.max_evaluations, samples=args.samples,
                   seed=args.seed, max_time=3600, alternatives=0)
    # One solve here first: a first use of the table method builds and caches the impact
    # table once, so local workers load it instead of each building it.
    solve_cell(problem, targets[0], cells_of(problem, args.grid)[0], options)

    summary = AtlasSummary(targets, args.grid)
    writer = JsonAtlasWriter(args.json, args.grid, targets, options) if args.json else None

    def consume(records):
        for record in records:
            summary.add(record)
            if writer:
                writer.add(record)

    if args.serial:
        started = time.perf_counter()
        consume(atlas(problem, targets, args.grid, options))
        seconds = time.perf_counter() - started
        where = "serial"
    else:
        from dask.distributed import Client, LocalCluster
        if args.scheduler:
            client = Client(args.scheduler)
            cluster = None
        else:
            cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        with client:
            workers = len(client.scheduler_info()["workers"])
            # Every worker imports the module and loads its impact table before the clock
            # starts: the time is the atlas's, not the cluster's start.
            client.run(solve_cell, problem, targets[0], cells_of(problem, args.grid)[0], options)
            started = time.perf_counter()
            consume(atlas(problem, targets, args.grid, options, client, window=args.window))
            seconds = time.perf_counter() - started
            where = f"{workers} Dask workers ({args.scheduler or 'LocalCluster'})"
        if cluster is not None:
            cluster.close()
    if writer:
        writer.close()
    cells = summary.cells
    print(f"atlas: {cells} problems ({args.grid[0]} x {args.grid[1]} cells x {len(targets)} targets) "
          f"solved on {where} in {seconds:.2f} s ({cells / seconds:.2f} problems/s); {summary.solved} solved")
    if args.out:
        draw(problem, targets, args.grid, summary, args.out)
        print(f"atlas: drawn to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
