"""`cmake --install` installs the package: the python component into a scratch prefix,
then imported from there alone (not from the build tree) and used once.

Arguments: the build directory and the install directory relative to the prefix
(CUEPLAN_PYTHON_INSTALL_DIR). Exits 77 (skipped) when numpy is missing.
"""
import os
import subprocess
import sys
import tempfile

try:
    import numpy  # noqa: F401
except ImportError as missing:  # pragma: no cover
    print(f"skipped: {missing}")
    sys.exit(77)

build, site = sys.argv[1], sys.argv[2]
with tempfile.TemporaryDirectory() as prefix:
    subprocess.run(["cmake", "--install", build, "--component", "python", "--prefix", prefix], check=True,
                   stdout=subprocess.DEVNULL)
    installed = os.path.join(prefix, site)
    for name in ("__init__.py", "_core.pyi", "py.typed"):
        assert os.path.exists(os.path.join(installed, "cueplan", name)), name
    env = dict(os.environ, PYTHONPATH=installed)
    code = ("import cueplan, sys; assert cueplan.__file__.startswith(sys.argv[1]), cueplan.__file__; "
            "r = cueplan.rebound(1.0, 45.0); assert r['status'] == 'ok', r; print(cueplan.__version__, r['rebound_angle_deg'])")
    done = subprocess.run([sys.executable, "-c", code, installed], env=env, cwd=prefix, capture_output=True, text=True)
    print(done.stdout, done.stderr)
    assert done.returncode == 0, done.stderr
print("installed and imported from", site)
