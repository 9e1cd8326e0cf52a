"""The Dask example (examples/dask_atlas.py) on a LocalCluster of two worker processes
gives the atlas the serial loop gives, record for record, and draws it.

Run by ctest with PYTHONPATH at build/python and CUEPLAN_EXAMPLES set; exits 77
(skipped) when dask.distributed, matplotlib or the module is missing.
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

try:
    import cueplan  # noqa: F401
    import dask.distributed  # noqa: F401
    import matplotlib  # noqa: F401
except ImportError as missing:  # pragma: no cover - a package not installed
    print(f"skipped: {missing} (scripts/setup.sh installs python3-distributed and python3-matplotlib)")
    sys.exit(77)

EXAMPLE = os.path.join(os.environ["CUEPLAN_EXAMPLES"], "dask_atlas.py")
# A small atlas: 4 x 3 cells, two targets; exact impacts, so no table is needed.
SMALL = ["--grid", "4", "3", "--target", "2.2,1.1", "--target", "1.0,0.4", "--method", "exact",
         "--max-evaluations", "250", "--samples", "20", "--seed", "4"]


def run(scratch, name, *extra):
    out = os.path.join(scratch, name + ".json")
    done = subprocess.run([sys.executable, EXAMPLE, *SMALL, "--json", out, *extra],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    with open(out) as f:
        return json.load(f), done.stdout


class DaskAtlas(unittest.TestCase):
    def test_two_workers_give_the_serial_atlas(self):
        with tempfile.TemporaryDirectory() as scratch:
            serial, _ = run(scratch, "serial", "--serial")
            picture = os.path.join(scratch, "atlas.png")
            dask, printed = run(scratch, "dask", "--workers", "2", "--out", picture)
            self.assertIn("2 Dask workers (LocalCluster)", printed)
            self.assertEqual(len(serial["records"]), 24)
            statuses = {r["status"] for r in serial["records"]}
            self.assertIn("solved", statuses)
            self.assertEqual(dask["records"], serial["records"])  # deliberate: determinism
            with open(picture, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main(verbosity=2)
