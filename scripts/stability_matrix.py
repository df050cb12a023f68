#!/usr/bin/env python3
"""Run the stability matrix of fix contact/dynamics (doc/stability.md): scripts/cdtools/stability_matrix.py.

    scripts/stability_matrix.py --out /work/stab-runs [--lmp build/lmp_cd] [--jobs 1]
                                [--only PATTERN] [--list] [--reuse]
"""

import os
import sys

# cdtools, found from this file (scripts/cdtools/__init__.py)
sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
from cdtools.stability_matrix import main

if __name__ == "__main__":
    sys.exit(main())
