#!/usr/bin/env python3
"""The marked numbers of the results pages' prose against the committed data
(studies/cdtools/page_numbers.py says how a marker reads).

    studies/page_numbers.py            one line per marked number that disagrees; exit 1 if any
    studies/page_numbers.py --update   rewrite those numbers from the data (same decimals and
                                       sign style) and list each change: read the sentences
                                       around them again, a verdict may have turned
"""

import argparse
import os
import sys

from cdtools import page_numbers

TOP = os.path.join(os.path.dirname(os.path.realpath(__file__)), os.pardir)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--update", action="store_true", help="rewrite the disagreeing numbers from the data")
    parser.add_argument("--root", default=TOP, help="the repository (default: this one)")
    args = parser.parse_args(argv)
    missing = [page for page in page_numbers.PAGES if not os.path.exists(os.path.join(args.root, page))]
    if missing:
        parser.error(f"--root {args.root}: no {', '.join(missing)} (not this project's repository)")
    if args.update:
        for page, line, key, old, new in page_numbers.update_pages(args.root):
            print(f"{page}:{line}: {key}: {old} -> {new}")
    stale = page_numbers.check_pages(args.root)
    for page, line, key, problem in stale:
        print(f"{page}:{line}: {key}: {problem}")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
