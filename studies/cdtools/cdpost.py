"""cdpost, the project's postprocessing program: where it is, and its results.csv."""

import csv
import math
import os
import shutil

from .run import BUILT_CDPOST

# The record inputs/in.chute writes into a run's folder as its chute stage starts (wall tops,
# sample rate, d, g and the scene's parameters); cdpost takes from it what it is not given.
RUN_RECORD = "chute.params"


def find_cdpost(given=None):
    """The cdpost executable: `given`, else the build's, else the one on PATH; None if none
    of them is executable."""
    candidates = [given] if given else [BUILT_CDPOST, shutil.which("cdpost") or ""]
    return next((c for c in candidates if c and os.access(c, os.X_OK)), None)


def read_results(path):
    """cdpost's results.csv (or fits.csv) -> {name: (value, error or None, unit)}; an empty
    value is nan."""
    rows = {}
    with open(path, newline="") as src:
        for row in csv.DictReader(src):
            value = float(row["value"]) if row["value"].strip() else math.nan
            error = float(row["error"]) if (row.get("error") or "").strip() else None
            rows[row["name"]] = (value, error, row.get("unit", ""))
    return rows
