#!/usr/bin/env python3
"""Every deck and command shown in README.md and doc/ runs as shown (ctest label docs).

    test_docs.py CASE --lmp build/lmp_cd --cdpost build/postproc/cdpost --work DIR
    test_docs.py pages|costs|page_rules

The cases `pages` (lengths: README.md, every page under doc/, the newcomer pages' words together;
no study log's sections or phrases),
`costs` (each deck's cost stated once) and `page_rules` (those rules tried on synthetic pages)
run no program: page_rules.py says what they check.

How the pages mark what they show (the test finds blocks by these marks):

  ```lammps          (Markdown) or `.. code-block:: LAMMPS` (reST): a complete deck. The case
                     `decks` runs it as shown with lmp_cd in a scratch folder.
  ```sh              commands. The case `commands` runs each block's commands in order in one
                     scratch folder that links the repository's inputs/, scripts/, studies/, bench/,
                     reference/, doc/ and build/, with lmp_cd and cdpost on the PATH.
  ```sh long         commands too long for a test (set-up, campaigns, studies, benchmarks).
                     The case `long_commands` checks them: every program of the repository
                     exists, every --option is one the program takes, every lmp_cd deck
                     exists and every -var names one of its variables.
  ```text            output, a synopsis or a fragment, marked as such: neither run nor checked.
  anything else      (indented blocks, other fences, reST literal blocks) must not show a
                     command or a deck: the case `unmarked` fails if one does.

The chute decks run shorter (a documented substitution, the only one): a command running
inputs/in.chute runs it on an 8 d cell of 60 grains with 3 d walls (those -var come first and
LAMMPS keeps the first value of an index variable), and every chute deck (in.chute,
in.default_scene) runs for a tenth of the chute time shown (its default when none is shown),
rounded to whole milliseconds; cdpost's --t-start and --t-end are scaled alike.

A deck or command fails on a non-zero exit status, or on a line of its output starting with
ERROR or WARNING (cdpost: "cdpost: error" or "cdpost: warning"). The case `example_decks`
applies the same rule to the decks in inputs/ on short runs. Standard library only.
"""

import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import unittest

import page_rules

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
PAGES = [os.path.join(TOP, "README.md")] + sorted(glob.glob(os.path.join(TOP, "doc", "*.md"))) + \
    sorted(glob.glob(os.path.join(TOP, "doc", "*.rst")))
LINKED = ("inputs", "scripts", "studies", "bench", "reference", "doc", "build")

SMALL_CELL = ["-var", "L", "8", "-var", "grains", "60", "-var", "wall_height", "3"]
TIME_SCALE = 0.1
DEFAULT_DURATION = {"in.chute": 10.0, "in.default_scene": 1.5}
# Programs that only run another one: their options (and the values of those listed) are skipped.
WRAPPERS = {"nice": {"-n"}, "taskset": {"-c"}, "/usr/bin/time": set(), "time": set(),
            "stdbuf": set(), "mpirun": {"-np", "-n"}, "mpiexec": {"-np", "-n"}, "perf": set()}
# A line of an unmarked block that starts with one of these is a command.
COMMAND_STARTS = ("lmp_cd", "build/", "cdpost", "cdref", "scripts/", "studies/", "bench/", "reference/",
                  "inputs/", "mpirun", "cmake", "ctest", "lmp ", "liggghts", "taskset", "nice ")
BAD_LINE = re.compile(r"^(ERROR|WARNING)|^cdpost: (error|warning)", re.M)


class Failure(Exception):
    pass


class Block:
    def __init__(self, page, line, kind, text):
        self.page, self.line, self.kind, self.text = page, line, kind, text

    def where(self):
        return f"{os.path.relpath(self.page, TOP)}:{self.line}"


def markdown_blocks(page, lines):
    blocks, i = [], 0
    while i < len(lines):
        fence = re.match(r"^ {0,3}```(.*)$", lines[i])
        if fence:
            info = fence.group(1).split()
            kind = {"lammps": "deck", "sh": "commands", "text": "text"}.get(info[0] if info else "", "unmarked")
            if kind == "commands" and info[1:2] == ["long"]:
                kind = "long"
            start, i = i + 1, i + 1
            while i < len(lines) and not re.match(r"^ {0,3}```\s*$", lines[i]):
                i += 1
            blocks.append(Block(page, start, kind, "\n".join(lines[start:i])))
            i += 1
            continue
        if lines[i].startswith("    ") and (i == 0 or not lines[i - 1].strip()):
            start = i
            while i < len(lines) and (lines[i].startswith("    ") or not lines[i].strip()):
                i += 1
            blocks.append(Block(page, start + 1, "unmarked", "\n".join(line[4:] for line in lines[start:i])))
            continue
        i += 1
    return blocks


def rest_blocks(page, lines):
    blocks, i = [], 0
    while i < len(lines):
        directive = re.match(r"^(\s*)\.\. (code-block|parsed-literal)::\s*(\S*)", lines[i])
        literal = lines[i].rstrip().endswith("::") and not lines[i].lstrip().startswith("..")
        if not (directive or literal):
            i += 1
            continue
        indent = len(directive.group(1)) if directive else len(lines[i]) - len(lines[i].lstrip())
        kind = "unmarked"
        if directive and directive.group(2) == "code-block":
            kind = {"lammps": "deck", "sh": "commands"}.get(directive.group(3).lower(), "unmarked")
        i += 1
        while i < len(lines) and re.match(r"^\s+:\w+:", lines[i]):  # directive options
            i += 1
        start, body = i, []
        while i < len(lines) and (not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > indent):
            body.append(lines[i])
            i += 1
        width = min((len(line) - len(line.lstrip()) for line in body if line.strip()), default=0)
        blocks.append(Block(page, start + 1, kind, "\n".join(line[width:] for line in body).strip("\n")))
    return blocks


def all_blocks():
    blocks = []
    for page in PAGES:
        with open(page) as src:
            lines = src.read().split("\n")
        blocks += (rest_blocks if page.endswith(".rst") else markdown_blocks)(page, lines)
    return blocks


def logical_lines(text):
    """Lines of a command block, backslash continuations joined, comments and blanks dropped."""
    out, pending = [], ""
    for line in text.split("\n"):
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        line = pending + line
        pending = ""
        tokens = shlex.split(line, comments=True)
        if tokens:
            out.append(tokens)
    return out


def segments(tokens):
    """A command line split at && and ;."""
    parts, current = [], []
    for token in tokens:
        if token in ("&&", ";"):
            parts.append(current)
            current = []
        else:
            current.append(token)
    return [p for p in parts + [current] if p]


def program_at(tokens):
    """Index of the program a command line runs (past variable assignments and wrappers)."""
    i = 0
    while i < len(tokens):
        if re.match(r"^[A-Z_]+=", tokens[i]):
            i += 1
            continue
        if tokens[i] in WRAPPERS:
            takes_value = WRAPPERS[tokens[i]]
            i += 1
            if tokens[i - 1] == "perf" and i < len(tokens) and tokens[i] == "record":
                i += 1
            while i < len(tokens) and tokens[i].startswith("-"):
                i += 2 if tokens[i] in takes_value else 1
            continue
        return i
    return len(tokens)


def option_value(tokens, option):
    return next((tokens[k + 1] for k in range(len(tokens) - 1) if tokens[k] == option), None)


def deck_variables(deck_path):
    """Index variables a deck (and the decks it includes from inputs/) defines."""
    names, decks = set(), [deck_path]
    while decks:
        with open(decks.pop()) as src:
            text = src.read()
        names |= set(re.findall(r"^variable\s+(\w+)\s+index\b", text, re.M))
        for included in re.findall(r"^include\s+\S*?(in\.\w+)\s*$", text, re.M):
            decks.append(os.path.join(TOP, "inputs", included))
    return names


def check_lmp_command(tokens, where):
    """The deck exists and every -var names one of its index variables (LAMMPS ignores others)."""
    deck = option_value(tokens, "-in")
    if deck is None:
        raise Failure(f"{where}: lmp_cd without -in: {shlex.join(tokens)}")
    path = os.path.join(TOP, deck)
    if not os.path.exists(path):
        raise Failure(f"{where}: no deck {deck}")
    known = deck_variables(path)
    for k, token in enumerate(tokens):
        if token in ("-var", "-v") and tokens[k + 1] not in known:
            raise Failure(f"{where}: {deck} has no variable {tokens[k + 1]}")
    return path


def scaled_time(value):
    return f"{max(0.01, round(float(value) * TIME_SCALE, 3)):g}"


def substituted(tokens, where):
    """The command as the test runs it (the chute decks shorter, see the module text)."""
    at = program_at(tokens)
    program = tokens[at] if at < len(tokens) else ""
    if os.path.basename(program) == "lmp_cd":
        deck = os.path.basename(check_lmp_command(tokens, where))
        if deck in DEFAULT_DURATION:
            shown = [tokens[k + 2] for k in range(len(tokens) - 2)
                     if tokens[k] == "-var" and tokens[k + 1] == "duration"]
            extra = (SMALL_CELL if deck == "in.chute" else []) + \
                ["-var", "duration", scaled_time(shown[0] if shown else DEFAULT_DURATION[deck])]
            return tokens[:at + 1] + extra + tokens[at + 1:]
    if os.path.basename(program) == "cdpost":
        tokens = list(tokens)
        for k in range(len(tokens) - 1):
            if tokens[k] in ("--t-start", "--t-end"):
                tokens[k + 1] = f"{float(tokens[k + 1]) * TIME_SCALE:g}"
    return tokens


def run_and_check(command, cwd, env, where):
    result = subprocess.run(["bash", "-c", command], cwd=cwd, env=env, capture_output=True, text=True,
                            timeout=600)
    output = result.stdout + result.stderr
    bad = BAD_LINE.search(output)
    if result.returncode != 0 or bad:
        line = output[bad.start():output.find("\n", bad.start())] if bad else output[-800:]
        raise Failure(f"{where}: `{command}` exited {result.returncode}: {line}")


def scratch(work, name):
    folder = os.path.join(work, name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    return folder


def tool_env(args, work):
    bin_dir = os.path.join(work, "bin")
    os.makedirs(bin_dir, exist_ok=True)
    for name, target in (("lmp_cd", args.lmp), ("cdpost", args.cdpost)):
        link = os.path.join(bin_dir, name)
        if os.path.lexists(link):
            os.remove(link)
        os.symlink(os.path.abspath(target), link)
    env = dict(os.environ)
    env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
    env["OMP_NUM_THREADS"] = "1"
    return env


def case_decks(args):
    decks = [b for b in all_blocks() if b.kind == "deck"]
    if not decks:
        raise Failure("no deck found in README.md or doc/")
    env = tool_env(args, args.work)
    for n, block in enumerate(decks):
        folder = scratch(args.work, f"deck{n}")
        with open(os.path.join(folder, "in.deck"), "w") as out:
            out.write(block.text + "\n")
        run_and_check("lmp_cd -in in.deck -log log.lammps", folder, env, block.where())
    print(f"{len(decks)} decks ran without ERROR or WARNING")


def case_commands(args):
    blocks = [b for b in all_blocks() if b.kind == "commands"]
    if not blocks:
        raise Failure("no ```sh block found in README.md or doc/")
    env = tool_env(args, args.work)
    count = 0
    for n, block in enumerate(blocks):
        folder = scratch(args.work, f"commands{n}")
        for name in LINKED:
            os.symlink(os.path.join(TOP, name), os.path.join(folder, name))
        for tokens in logical_lines(block.text):
            command = " && ".join(shlex.join(substituted(part, block.where())) for part in segments(tokens))
            run_and_check(command, folder, env, block.where())
            count += 1
    print(f"{count} commands of {len(blocks)} blocks ran without ERROR or WARNING")


def help_text(path, tokens):
    """What a repository script says it takes: its --help (and its subcommand's), or its source."""
    with open(path) as src:
        source = src.read()
    if not source.startswith("#!") or "python" not in source.split("\n")[0]:
        return source
    text = subprocess.run([sys.executable, path, "--help"], capture_output=True, text=True).stdout
    if len(tokens) > 1 and not tokens[1].startswith("-"):
        text += subprocess.run([sys.executable, path, tokens[1], "--help"], capture_output=True, text=True).stdout
    return text


def check_long_command(tokens, where, args):
    at = program_at(tokens)
    if at >= len(tokens):
        return
    command = tokens[at:]
    program = command[0]
    options = [t.split("=")[0] for t in command[1:] if re.match(r"^--[\w-]+(=|$)", t)]
    if os.path.basename(program) == "lmp_cd":
        check_lmp_command(command, where)
        return
    if program == "cdpost":
        taken = subprocess.run([args.cdpost, command[1], "--help"], capture_output=True, text=True).stdout
    elif "/" in program:
        path = os.path.join(TOP, program)
        if not os.access(path, os.X_OK):
            raise Failure(f"{where}: {program} does not exist or is not executable")
        if program.startswith("build/"):
            return
        taken = help_text(path, command)
    else:
        return  # a system program (lmp, cmake, hyperfine, ...): not the repository's to check
    for option in options:
        if option not in taken:
            raise Failure(f"{where}: {program} takes no option {option}")


def case_long_commands(args):
    blocks = [b for b in all_blocks() if b.kind == "long"]
    if not blocks:
        raise Failure("no ```sh long block found in README.md or doc/")
    count = 0
    for block in blocks:
        for tokens in logical_lines(block.text):
            for part in segments(tokens):
                check_long_command(part, block.where(), args)
                count += 1
    print(f"{count} long commands of {len(blocks)} blocks checked")


def case_unmarked(args):
    blocks = [b for b in all_blocks() if b.kind == "unmarked"]
    for block in blocks:
        lines = [line.strip() for line in block.text.split("\n")]
        for line in lines:
            if line.startswith(COMMAND_STARTS) and not line.startswith("ERROR"):
                raise Failure(f"{block.where()}: a command in a block that is not run or checked "
                              f"(mark it ```sh or ```sh long): {line}")
        if any(re.match(r"^fix\s+\S+\s+\S+\s+contact/dynamics", line) for line in lines) and \
                any(re.match(r"^run\s", line) for line in lines):
            raise Failure(f"{block.where()}: a deck in a block that is not run (mark it ```lammps)")
    print(f"{len(blocks)} unmarked blocks hold no command and no deck")


def case_example_decks(args):
    """The decks of inputs/ on short runs: the default scene (stage all, adaptive step) and
    in.chute on the small cell, deposition then flow at a fixed step then its continuation."""
    env = tool_env(args, args.work)
    folder = scratch(args.work, "example_decks")
    os.symlink(os.path.join(TOP, "inputs"), os.path.join(folder, "inputs"))
    small = shlex.join(SMALL_CELL)
    for command in (
            "lmp_cd -in inputs/in.default_scene -var duration 0.05 -log scene.log",
            f"lmp_cd -in inputs/in.chute {small} -var stage deposition -log deposition.log",
            f"lmp_cd -in inputs/in.chute {small} -var stage flow -var adapt_dt no -var dt 5e-5 "
            "-var duration 0.05 -log flow.log",
            f"lmp_cd -in inputs/in.chute {small} -var stage flow -var adapt_dt no -var dt 5e-5 "
            "-var start chute.restart -var duration 0.1 -log continued.log"):
        run_and_check(command, folder, env, "inputs/")
    print("the example decks ran without ERROR or WARNING")


def tree_files(pattern_lists):
    """{path relative to the top: text} of the files the glob patterns match."""
    files = {}
    for pattern in pattern_lists:
        for path in glob.glob(os.path.join(TOP, pattern), recursive=True):
            with open(path) as src:
                files[os.path.relpath(path, TOP)] = src.read()
    return files


REFERENCE_PAGES = ("README.md", "doc/**/*.md", "doc/**/*.rst")
# The campaign's results pages: their length and links are checked as the reference pages' are.
RESULTS_PAGES = ("results/**/README.md",)


def report(problems, passed):
    if problems:
        raise Failure("\n".join(problems))
    print(passed)


def case_pages(args):
    pages = tree_files(REFERENCE_PAGES + RESULTS_PAGES)
    total = sum(page_rules.word_count(pages[path]) for path in page_rules.NEWCOMER_PAGES if path in pages)
    links = page_rules.link_problems(pages, lambda path: os.path.exists(os.path.join(TOP, path)))
    report(page_rules.length_problems(pages) + page_rules.history_problems(pages) + links,
           f"{len(pages)} pages within their lengths, their links resolved; the newcomer pages {total} words "
           f"together (at most {page_rules.NEWCOMER_WORD_LIMIT})")


def case_costs(args):
    files = tree_files(REFERENCE_PAGES + ("inputs/in.*",))
    report(page_rules.cost_problems(files), "every deck's cost is stated once")


def case_page_rules(args):
    suite = unittest.defaultTestLoader.discover(HERE, pattern="test_page_rules.py", top_level_dir=HERE)
    if not unittest.TextTestRunner(verbosity=2).run(suite).wasSuccessful():
        raise Failure("the page rules misjudge a synthetic page (above)")


CASES = {"decks": case_decks, "commands": case_commands, "long_commands": case_long_commands,
         "unmarked": case_unmarked, "example_decks": case_example_decks,
         "pages": case_pages, "costs": case_costs, "page_rules": case_page_rules}
# The cases that run lmp_cd or cdpost (the others read the pages only).
RUNS_PROGRAMS = {"decks", "commands", "long_commands", "example_decks"}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--lmp", help="lmp_cd")
    parser.add_argument("--cdpost", help="cdpost")
    parser.add_argument("--work", help="scratch folder")
    args = parser.parse_args()
    if args.case in RUNS_PROGRAMS:
        missing = [option for option in ("lmp", "cdpost", "work") if getattr(args, option) is None]
        if missing:
            parser.error(f"the case {args.case} needs " + ", ".join("--" + option for option in missing))
        args.work = os.path.join(os.path.abspath(args.work), args.case)
        os.makedirs(args.work, exist_ok=True)
    try:
        CASES[args.case](args)
    except Failure as failure:
        sys.exit(f"FAIL: {failure}")  # status 1, the reason on stderr


if __name__ == "__main__":
    main()
