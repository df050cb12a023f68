"""What the checks of the study scripts share: a failed check ends the test with its message, and a
script of studies/ is loaded as a module (its own imports resolved from studies/)."""

import importlib.util
import os
import sys

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, os.pardir)
STUDIES = os.path.join(TOP, "studies")


def check(condition, message):
    if not condition:
        sys.exit(f"FAILED: {message}")


def load_study(name):
    """studies/NAME.py as a module named NAME."""
    if STUDIES not in sys.path:
        sys.path.insert(0, STUDIES)
    spec = importlib.util.spec_from_file_location(name, os.path.join(STUDIES, name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
