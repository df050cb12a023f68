#!/usr/bin/env python3
"""Where a step of fix contact/dynamics goes, from perf records: scripts/cdtools/step_profile.py
(its usage there).
"""

import os
import sys

# cdtools, found from this file (scripts/cdtools/__init__.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "scripts"))
from cdtools.step_profile import main

if __name__ == "__main__":
    sys.exit(main())
