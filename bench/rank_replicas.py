#!/usr/bin/env python3
"""Replica runs of the chute on several rank counts, compared: scripts/cdtools/rank_replicas.py
(its usage there).
"""

import os
import sys

# cdtools, found from this file (scripts/cdtools/__init__.py)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir, "scripts"))
from cdtools.rank_replicas import main

if __name__ == "__main__":
    sys.exit(main())
