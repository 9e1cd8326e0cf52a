"""Impact tables for method="table": loaded from a cache directory, or built there once
(about 30 s on 2 cores), then kept for the life of the process.

The cache directory is the command line's: $CUEPLAN_CACHE_DIR, else
$XDG_CACHE_HOME/cueplan, else ~/.cache/cueplan, so a table the command line built is
loaded here and the other way round.
"""
from __future__ import annotations

import os
import tempfile
import threading
from typing import Dict, Optional, Tuple

from . import _core

_tables: Dict[Tuple, "_core.ImpactTable"] = {}
_lock = threading.Lock()


def default_cache_dir() -> str:
    """The directory impact tables are cached in (see the module's docstring)."""
    for name, tail in (("CUEPLAN_CACHE_DIR", ""), ("XDG_CACHE_HOME", "cueplan")):
        value = os.environ.get(name)
        if value:
            return os.path.join(value, tail) if tail else value
    home = os.environ.get("HOME")
    if home:
        return os.path.join(home, ".cache", "cueplan")
    return os.path.join(tempfile.gettempdir(), "cueplan")


def table_for(params: "_core.CushionParams", cache_dir: Optional[str] = None) -> Optional["_core.ImpactTable"]:
    """The impact table of a cushion, or None for a model the table does not serve
    (han_2005: every impact is a closed form)."""
    if params.model != "mathavan_2010":
        return None
    directory = default_cache_dir() if cache_dir is None else os.fspath(cache_dir)
    key = (params.mass, params.radius, params.cushion_height, params.mu_cushion, params.mu_table,
           params.restitution, params.rigid_speed_limit, directory)
    with _lock:
        table = _tables.get(key)
        if table is None:
            table = _core.load_or_build_table(params, directory)
            _tables[key] = table
        return table
