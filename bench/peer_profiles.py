#!/usr/bin/env python3
"""Performance profiles (Dolan and Moré 2002) of the solvers of bench/peers/peer_bench.

    bench/peer_profiles.py --out PREFIX [--screen SCREEN.csv] [--time-limit S] [--ours NAME]
                           [--leave-out NAME,...] [--best-variant] [--within F [--answers ANSWERS.csv]]
                           SOLVES.csv...

An instance is one problem, one start (cold or warm) and one target error; a solver's cost on it
is its CPU time if it reached the target within the time limit, else infinite. rho_s(tau) is
the fraction of instances a solver solves within tau times the best solver's time. Writes
PREFIX.md (tables: per group and target, per class; the screening) and PREFIX.png (the
profiles: a panel per group and target). Groups: ordinary (chute_*, pile_*), hard (stall_*,
saved_hard). --time-limit: a solve over S CPU seconds counts as not solved (the screening's
limit may be longer). --ours: the solver the per-class table and the hard check are about (ours;
ours_newton for the Newton polish); --leave-out: solvers dropped from the rows (e.g. one of the two).
A Siconos variant (SOLVER[KEY=VALUE+...]) is a solver of its own; --best-variant keeps of each
family (its SOLVER) the default and the variant that solves the most instances (ties: the least
time summed over those it solves), and drops the other variants.
--within F: the second reading. Siconos's error divides |F(r)| by the answer's own size, so an
answer whose |r| grows along W's null space (a self-stress of sticking contacts) meets it without
meeting the law; a solved answer whose error at the problem's scale (|F| over max(|q|, |r0|,
|W r0 + q|), r0 the warm start: peer_bench's error_at_problem_scale) is over F times the target
counts as not solved ('inflated'). The scales are read from SOLVES.csv, or from ANSWERS.csv: the
same solves run again with them recorded (each solve is deterministic; a solve solved in one run
and not in the other counts as not solved, 'not_reproduced'). The answers' reading is listed.
Several SOLVES.csv are read as one run. Standard library and gnuplot.
"""

import argparse
import collections
import csv
import math
import os
import statistics
import subprocess
import tempfile

TAUS = [10 ** (k / 20) for k in range(0, 61)]  # 1 to 1000
OURS = "ours"  # --ours


def group_of(cls):
    return "ordinary" if cls.startswith(("chute_", "pile_")) else "hard"


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def costs(rows):
    """{(group, target): {instance: {solver: seconds or inf}}} and the class of each instance."""
    table = collections.defaultdict(lambda: collections.defaultdict(dict))
    classes = {}
    for r in rows:
        instance = (r["class"], r["problem"], r["start"])
        classes[instance] = r["class"]
        seconds = float(r["seconds"]) if r["status"] == "solved" else math.inf
        table[(group_of(r["class"]), float(r["target"]))][instance][r["solver"]] = max(seconds, 1e-6)
    return table, classes


def ratios(instances):
    """{solver: [ratio per instance]} (inf: not solved)."""
    out = collections.defaultdict(list)
    for per_solver in instances.values():
        best = min(per_solver.values())
        for solver, t in per_solver.items():
            out[solver].append(t / best if math.isfinite(t) else math.inf)
    return out


def share(values, tau):
    return sum(1 for v in values if math.isfinite(v) and v <= tau) / len(values) if values else 0.0


def profile_tables(table, solvers):
    keys = sorted(table, key=lambda k: (k[0] != "ordinary", -k[1]))
    lines = ["| solver | " + " | ".join(f"{g} {t:g}" for g, t in keys) + " |",
             "|---|" + "---|" * len(keys)]
    per_key = {k: ratios(table[k]) for k in keys}
    for s in solvers:
        cells = []
        for k in keys:
            r = per_key[k].get(s, [])
            cells.append(f"{100 * share(r, math.inf):.0f} / {100 * share(r, 1.0):.0f}")
        lines.append(f"| {s} | " + " | ".join(cells) + " |")
    counts = " · ".join(f"{g} {t:g}: {len(table[(g, t)])}" for g, t in keys)
    return lines, f"Instances (problem x start): {counts}."


def class_table(rows, solvers):
    """Per class and target: ours solved, ours fastest, the solver fastest most often."""
    by = collections.defaultdict(lambda: collections.defaultdict(dict))
    for r in rows:
        seconds = float(r["seconds"]) if r["status"] == "solved" else math.inf
        by[(r["class"], float(r["target"]))][(r["problem"], r["start"])][r["solver"]] = seconds
    lines = ["| class | target | instances | ours solved | ours fastest | fastest most often | ours median s "
             "| its median s |",
             "|---|---|---|---|---|---|---|---|"]
    for (cls, target) in sorted(by, key=lambda k: (k[0], -k[1])):
        inst = by[(cls, target)]
        wins = collections.Counter()
        for per in inst.values():
            best = min(per.values())
            if math.isfinite(best):
                wins.update(s for s, t in per.items() if t == best)
        ours = [per.get(OURS, math.inf) for per in inst.values()]
        leader = max(wins, key=wins.get) if wins else "none"
        theirs = [per.get(leader, math.inf) for per in inst.values()]
        lines.append(f"| {cls} | {target:g} | {len(inst)} | {sum(map(math.isfinite, ours))} | {wins.get(OURS, 0)} | "
                     f"{leader} ({wins.get(leader, 0)}) | {median(ours)} | {median(theirs)} |")
    return lines


def median(values):
    finite = sorted(v for v in values if math.isfinite(v))
    return f"{finite[len(finite) // 2]:.3g}" if finite else "-"


def seconds_by_instance(rows):
    """{(class, problem, start, target): {solver: seconds, inf if not solved}}."""
    by = collections.defaultdict(dict)
    for r in rows:
        seconds = float(r["seconds"]) if r["status"] == "solved" else math.inf
        by[(r["class"], r["problem"], r["start"], float(r["target"]))][r["solver"]] = seconds
    return by


def hard_check(rows):
    """Hard instances where a Siconos solver reached the target faster than ours (or ours failed)."""
    by = seconds_by_instance(r for r in rows if group_of(r["class"]) == "hard")
    lost = []
    for key, per in sorted(by.items()):
        ours = per.get(OURS, math.inf)
        faster = sorted((t, s) for s, t in per.items() if s != OURS and t < ours)
        if faster:
            lost.append(f"{key[0]}/{key[1]} {key[2]} {key[3]:g}: ours "
                        f"{ours:.3g} s, " + ", ".join(f"{s} {t:.3g} s" for t, s in faster[:3]))
    return len(by), lost


def targets_summary(rows):
    """Ours against the field over every instance: solved, fastest (a tie counts), and where ours and
    another solver both solve, the median of the fastest other's time over ours per target, for
    every other solver and for Siconos's defaults alone (names without options)."""
    by = seconds_by_instance(rows)
    solved = fastest = anyone = 0
    slower = {"every other solver": collections.defaultdict(list), "Siconos's defaults": collections.defaultdict(list)}
    for key, per in by.items():
        ours = per.get(OURS, math.inf)
        best = min(per.values())
        solved += math.isfinite(ours)
        anyone += math.isfinite(best)
        fastest += math.isfinite(ours) and ours == best
        others = {s: t for s, t in per.items() if s != OURS}
        defaults = {s: t for s, t in others.items() if "[" not in s and not s.startswith("ours")}
        for name, group in (("every other solver", others), ("Siconos's defaults", defaults)):
            best_other = min(group.values(), default=math.inf)
            if math.isfinite(ours) and math.isfinite(best_other):
                slower[name][key[3]].append(best_other / max(ours, 1e-9))
    n = len(by)
    lines = [f"Targets: {OURS} solves {solved} of {n}; it is the fastest on {fastest} of {n} "
             f"({100 * fastest / n:.1f} %) and on {fastest} of the {anyone} that any solver solves." if n else
             "Targets: no instance.", ""]
    for name, per_target in slower.items():
        cells = [f"{t:g}: {statistics.median(v):.2f} ({len(v)})" for t, v in sorted(per_target.items(), reverse=True)]
        lines.append(f"- where both solve, the fastest of {name} over {OURS}, median (instances): " + " · ".join(cells))
    return lines


def instance_key(r):
    return (r["class"], r["problem"], r["solver"], r["start"], float(r["target"]))


def at_problem_scale(rows, answers, within):
    """Marks each solved row whose answer is over `within` times its target at the problem's scale
    'inflated' (and one whose solve in `answers` did not solve 'not_reproduced'); returns
    {solver: Counter of the marks}."""
    scales = {instance_key(a): a for a in answers}
    marks = collections.defaultdict(collections.Counter)
    for r in rows:
        if r["status"] != "solved":
            continue
        again = scales.get(instance_key(r))
        if again is None:
            raise SystemExit(f"peer_profiles: no answer in --answers for {' '.join(map(str, instance_key(r)))}")
        if again["status"] != "solved":
            r["status"] = "not_reproduced"
        elif float(again["error_at_problem_scale"]) > within * float(r["target"]):
            r["status"] = "inflated"
        marks[r["solver"]][r["status"]] += 1
    return marks


def answers_table(marks, within):
    lines = [f"Solved answers read at the problem's scale (over {within:g} x the target: inflated):", "",
             "| solver | solved | inflated | not reproduced |", "|---|---|---|---|"]
    for s, m in marks.items():
        lines.append(f"| {s} | {m['solved']} | {m['inflated']} | {m['not_reproduced']} |")
    return lines


def family(solver):
    return solver.split("[", 1)[0]


def best_variants(rows):
    """The rows of each family's default and of its variant solving the most instances."""
    solved = collections.Counter()
    spent = collections.Counter()
    for r in rows:
        if r["status"] == "solved":
            solved[r["solver"]] += 1
            spent[r["solver"]] += float(r["seconds"])
    best = {}
    for s in dict.fromkeys(r["solver"] for r in rows):
        if "[" in s:
            key = (solved[s], -spent[s])
            if family(s) not in best or key > best[family(s)][0]:
                best[family(s)] = (key, s)
    kept = {s for _, s in best.values()}
    return [r for r in rows if "[" not in r["solver"] or r["solver"] in kept]


def screen_table(rows):
    lines = ["| solver | screening problems solved at 1e-3 (cold, warm) | outcomes |", "|---|---|---|"]
    by = collections.defaultdict(list)
    for r in rows:
        by[r["solver"]].append(r["status"])
    for s, statuses in by.items():
        counts = collections.Counter(statuses)
        lines.append(f"| {s} | {counts['solved']} of {len(statuses)} | "
                     + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())) + " |")
    return lines


def draw(table, solvers, png):
    keys = sorted(table, key=lambda k: (k[0] != "ordinary", -k[1]))
    with tempfile.TemporaryDirectory() as work:
        script = [f"set terminal pngcairo noenhanced size 1500,{450 * ((len(keys) + 2) // 3)} font ',10'",
                  f"set output '{png}'", f"set multiplot layout {(len(keys) + 2) // 3},3",
                  "set logscale x", "set xrange [1:1000]", "set yrange [0:1.02]", "set key bottom right font ',8'",
                  "set xlabel 'tau (time / best time)'", "set ylabel 'fraction of instances'"]
        for k in keys:
            r = ratios(table[k])
            plots = []
            for i, s in enumerate(solvers):
                path = os.path.join(work, f"{k[0]}_{k[1]:g}_{i}.dat")
                with open(path, "w") as f:
                    f.writelines(f"{tau} {share(r.get(s, []), tau)}\n" for tau in TAUS)
                width = 3 if s == OURS else 1
                plots.append(f"'{path}' with steps lw {width} title '{s}'")
            script += [f"set title '{k[0]}, error {k[1]:g} ({len(table[k])} instances)'", "plot " + ", ".join(plots)]
        script.append("unset multiplot")
        subprocess.run(["gnuplot"], input="\n".join(script), text=True, check=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--screen")
    parser.add_argument("--time-limit", type=float, default=math.inf)
    parser.add_argument("--ours", default="ours")
    parser.add_argument("--leave-out", default="")
    parser.add_argument("--best-variant", action="store_true")
    parser.add_argument("--within", type=float, help="the second reading: answers within F x the target "
                        "at the problem's scale")
    parser.add_argument("--answers", help="the solves run again with their scales (default: SOLVES.csv's own)")
    parser.add_argument("solves", nargs="+")
    args = parser.parse_args()
    global OURS
    OURS = args.ours
    left_out = set(filter(None, args.leave_out.split(",")))
    rows = [r for path in args.solves for r in read(path) if r["solver"] not in left_out]
    for r in rows:
        if r["status"] == "solved" and float(r["seconds"]) > args.time_limit:
            r["status"] = "time_limit"
    marks = None
    if args.within is not None:
        answers = read(args.answers) if args.answers else rows
        if answers and "error_at_problem_scale" not in answers[0]:
            parser.error(f"{args.answers or args.solves[0]}: no error_at_problem_scale column (peer_bench's)")
        marks = at_problem_scale(rows, answers, args.within)
    if args.best_variant:
        rows = best_variants(rows)
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    table, _ = costs(rows)
    profile, counts = profile_tables(table, solvers)
    total, lost = hard_check(rows)
    lines = ["Solved / fastest, % of instances (performance profile at tau = infinity and tau = 1):", "",
             *profile, "", counts, "", *targets_summary(rows), "", *class_table(rows, solvers), "",
             f"Hard instances (problem x start x target) where another solver reached the target faster than {OURS}: "
             f"{len(lost)} of {total}.", ""]
    lines += [f"- {line}" for line in lost]
    if marks is not None:
        lines += ["", *answers_table(marks, args.within)]
    if args.screen:
        lines += ["", "Screening:", "", *screen_table(read(args.screen))]
    with open(args.out + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    draw(table, solvers, args.out + ".png")


if __name__ == "__main__":
    main()
