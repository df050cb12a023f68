#!/usr/bin/env python3
"""Does the domain-decomposed Gauss-Seidel solve the same contact problem as one rank? The tool:
scripts/cdtools/rank_solutions.py (its usage there).
"""

import os
import sys

# cdtools, found from this file (scripts/cdtools/__init__.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "scripts"))
from cdtools.rank_solutions import main

if __name__ == "__main__":
    sys.exit(main())
