"""The rules that keep README.md and doc/ reference pages (test_docs.py, cases `pages` and `costs`).

Lengths (`length_problems`):
  README.md at most 100 lines; results/README.md (the campaign's results, read in ten minutes; its
  tables live on the pages it links) at most 250; every page under doc/ (.md, .rst, in any folder
  but doc/notes/) at most 300; the seven pages a user reads first (NEWCOMER_PAGES) at most 6000
  words together (whitespace-separated, as `wc -w` counts: half an hour of reading; measurements
  and studies live on the reference pages they link). doc/notes/
  holds dated notebooks, doc/notes/YYYY-MM-DD-topic.md, of any length: studies, superseded
  settings and corrected figures live there or in the git history, and no reference page needs
  them to be read.

Links (`link_problems`): every relative link and image of a Markdown page, [text](target) or
![text](target), names a file or folder that exists (relative to the page; an anchor after # and
links with a scheme such as https: are not checked).

History (`history_problems`): a reference page (README.md, doc/ but doc/notes/) has no section
named Open, Earlier or History and none of the phrases of a study log that HISTORY matches
("measured at commit", "not kept", "first reported", "previous defaults", ...): those go to the
git history or to a dated note.

Costs (`cost_problems`): each deck of inputs/ has its cost stated once. The statement that
gives it carries a marker naming the deck, in a comment of the page's language:

  Markdown   <!-- cost: in.default_scene -->
  reST       .. cost: in.chute

inside the statement it marks, or alone just above it (a statement of markers only marks the
next statement of its page).

Every other statement about that deck that gives a CPU time is an error: it links to the marked
one instead, or gives its cost relative to it ("1.4x the defaults"). A statement is a paragraph,
a list item, a table, a fenced block, or a run of comment lines in a deck of inputs/; it is about
a deck when it, or the heading of its section, names the deck (by its file name or by one of the
names in DECK_NAMES), and every comment in a deck's own file is about that deck. A CPU time is a
phrase CPU_TIME matches ("22 CPU s", "half a CPU minute", "minutes on one core", "a day of one
core", "core hours"). Pages under doc/notes/ are not read. Standard library only.
"""

import os
import re

README_LIMIT = 100
RESULTS_README = "results/README.md"
RESULTS_LIMIT = 250
PAGE_LIMIT = 300
NEWCOMER_PAGES = ("README.md", "doc/scene.md", "doc/fix_contact_dynamics.rst", "doc/chute.md", "doc/postproc.md",
                  "doc/soft_to_rigid.md", "doc/plane_shear.md")
NEWCOMER_WORD_LIMIT = 6000
NOTES = "doc/notes/"
NOTE_NAME = re.compile(r"^\d{4}-\d{2}-\d{2}-[a-z0-9][a-z0-9-]*\.md$")

HISTORY = re.compile(r"measured at commit|\bat commit [0-9a-f]{7}|\bnot kept\b|\bfirst reported\b|"
                     r"\breported (here )?earlier\b|\bsince deleted\b|\bprevious defaults?\b", re.I)
HISTORY_HEADING = re.compile(r"^(open|open questions|earlier\b.*|history)$", re.I)

# Names the pages use for a deck of inputs/, besides its file name.
DECK_NAMES = {
    "in.default_scene": (r"default[ _]scene",),
    "in.chute": (r"45 d scene", r"chute deck"),
}
CPU_TIME = re.compile(
    r"\bCPU[ -]?(s|seconds?|min|minutes?|h|hours?|days?)\b"
    r"|\b(seconds?|minutes?|hours?|days?) (of|on) (one|a|each|a single) (CPU|core)\b"
    r"|\bcore[ -]?(seconds?|minutes?|hours?|days?)\b", re.I)
MARKER = re.compile(r"(?:<!--|^\s*\.\.|^\s*#)\s*cost:\s*(\S+?)\s*(?:-->|$)", re.M)


def line_count(text):
    return len(text.splitlines())


def word_count(text):
    return len(text.split())


def is_reference_page(path):
    return path.startswith("doc/") and not path.startswith(NOTES) and path.endswith((".md", ".rst"))


def length_problems(pages):
    """pages: {path relative to the top: text}. One line per page over its limit."""
    problems = []
    for path, text in sorted(pages.items()):
        if path.startswith(NOTES):
            if not NOTE_NAME.match(path[len(NOTES):]):
                problems.append(f"{path}: a note is named doc/notes/YYYY-MM-DD-topic.md")
            continue
        limit = (README_LIMIT if path == "README.md" else RESULTS_LIMIT if path == RESULTS_README
                 else PAGE_LIMIT if is_reference_page(path) else None)
        if limit is not None and line_count(text) > limit:
            problems.append(f"{path}: {line_count(text)} lines, more than {limit}: move studies and history "
                            f"to the git log or to {NOTES}YYYY-MM-DD-topic.md")
    missing = [path for path in NEWCOMER_PAGES if path not in pages]
    if missing:
        problems.append(f"a newcomer page is missing: {', '.join(missing)}")
    total = sum(word_count(pages[path]) for path in NEWCOMER_PAGES if path in pages)
    if total > NEWCOMER_WORD_LIMIT:
        counts = ", ".join(f"{path} {word_count(pages[path])}" for path in NEWCOMER_PAGES if path in pages)
        problems.append(f"the newcomer pages hold {total} words together, more than {NEWCOMER_WORD_LIMIT} ({counts}): "
                        "move measurements and studies to the reference pages they link")
    return problems


LINK = re.compile(r"\]\(([^)\s]+)\)")


def link_problems(pages, exists):
    """pages: {path relative to the top: text}; exists(path relative to the top) says whether a file
    or folder is there. One line per relative link of a Markdown page that names nothing."""
    problems = []
    for path, text in sorted(pages.items()):
        if not path.endswith(".md"):
            continue
        for k, line in enumerate(text.split("\n")):
            for match in LINK.finditer(line):
                target = match.group(1).split("#")[0]
                if not target or re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):
                    continue
                resolved = os.path.normpath(os.path.join(os.path.dirname(path), target))
                if not exists(resolved):
                    problems.append(f"{path}:{k + 1}: the link {match.group(1)} names nothing ({resolved})")
    return problems


def headings(text):
    """(line number, title) of the Markdown and reST headings of a page, code blocks skipped."""
    lines, found, fence = text.split("\n"), [], False
    for k, line in enumerate(lines):
        if re.match(r"^ {0,3}(```|~~~)", line):
            fence = not fence
        elif not fence and re.match(r"^#{1,6}\s", line):
            found.append((k + 1, line.lstrip("#").strip()))
        elif not fence and line.strip() and k + 1 < len(lines) and re.match(r"^([=\-~^])\1{2,}\s*$", lines[k + 1]):
            found.append((k + 1, line.strip()))
    return found


def history_problems(pages):
    """pages: {path relative to the top: text}. One line per section or phrase of a study log."""
    problems = []
    for path, text in sorted(pages.items()):
        if not (path == "README.md" or is_reference_page(path)):
            continue
        for line, title in headings(text):
            if HISTORY_HEADING.match(title):
                problems.append(f"{path}:{line}: a section '{title}' on a reference page: move it to the git "
                                f"history or to {NOTES}YYYY-MM-DD-topic.md")
        for k, line in enumerate(text.split("\n")):
            for match in HISTORY.finditer(line):
                problems.append(f"{path}:{k + 1}: '{match.group(0)}' is a study log's phrase: say what is, "
                                f"and keep how it came to be in the git history or in {NOTES}")
    return problems


class Statement:
    def __init__(self, path, line, text, heading):
        self.path, self.line, self.text, self.heading = path, line, text, heading
        self.markers = MARKER.findall(text)

    def where(self):
        return f"{self.path}:{self.line}"

    def gives_cpu_time(self):
        return CPU_TIME.search(MARKER.sub("", self.text)) is not None

    def excerpt(self):
        match = CPU_TIME.search(MARKER.sub("", self.text))
        flat = " ".join(MARKER.sub("", self.text).split())
        at = flat.find(match.group(0)) if match else 0
        return flat[max(0, at - 60):at + 40]


def markdown_statements(path, text):
    statements, heading, lines, i = [], "", text.split("\n"), 0
    while i < len(lines):
        line = lines[i]
        if re.match(r"^ {0,3}(```|~~~)", line):
            start, i = i, i + 1
            while i < len(lines) and not re.match(r"^ {0,3}(```|~~~)\s*$", lines[i]):
                i += 1
            statements.append(Statement(path, start + 1, "\n".join(lines[start:i + 1]), heading))
            i += 1
        elif re.match(r"^#{1,6}\s", line):
            heading, i = line, i + 1
        elif not line.strip():
            i += 1
        else:
            start = i
            while i < len(lines) and lines[i].strip() and not re.match(r"^(#{1,6}\s| {0,3}(```|~~~))", lines[i]):
                i += 1
            statements += split_list_items(path, start, lines[start:i], heading)
    return statements


def split_list_items(path, start, block, heading):
    """A block of lines: one statement, or one per list item when it is a list."""
    starts = [k for k, line in enumerate(block) if re.match(r"^\s*([-*+]|\d+\.)\s", line)]
    if not starts or block[0].lstrip().startswith("|"):
        return [Statement(path, start + 1, "\n".join(block), heading)]
    bounds = ([0] if starts[0] else []) + starts + [len(block)]
    return [Statement(path, start + a + 1, "\n".join(block[a:b]), heading) for a, b in zip(bounds, bounds[1:])]


def rest_statements(path, text):
    statements, heading, lines, i = [], "", text.split("\n"), 0
    underline = re.compile(r"^([=\-~^\"'`#*+])\1+\s*$")
    while i < len(lines):
        if not lines[i].strip():
            i += 1
            continue
        if i + 1 < len(lines) and underline.match(lines[i + 1]) and not underline.match(lines[i]):
            heading, i = lines[i], i + 2
            continue
        start = i
        while i < len(lines) and lines[i].strip():
            i += 1
        statements.append(Statement(path, start + 1, "\n".join(lines[start:i]), heading))
    return statements


def deck_statements(path, text):
    """The runs of comment lines of a deck (a line of only # separates two)."""
    statements, run, start = [], [], 0
    for k, line in enumerate(text.split("\n") + [""]):
        comment = re.match(r"^\s*#(.*)$", line)
        if comment and comment.group(1).strip():
            if not run:
                start = k
            run.append(line)
            continue
        if run:
            statements.append(Statement(path, start + 1, "\n".join(run), ""))
            run = []
    return statements


def with_markers_moved_down(statements):
    """A statement of markers only gives them to the next statement of its file."""
    out = []
    for k, statement in enumerate(statements):
        if statement.markers and not MARKER.sub("", statement.text).strip() and k + 1 < len(statements):
            statements[k + 1].markers += statement.markers
            continue
        out.append(statement)
    return out


def statements_of(files):
    out = []
    for path, text in sorted(files.items()):
        if path.startswith(NOTES):
            continue
        if path.startswith("inputs/in."):
            out += deck_statements(path, text)
        elif path.endswith(".rst"):
            out += with_markers_moved_down(rest_statements(path, text))
        elif path.endswith(".md"):
            out += with_markers_moved_down(markdown_statements(path, text))
    return out


def names_deck(text, deck):
    patterns = (r"\b" + re.escape(deck) + r"(?![\w.])",) + DECK_NAMES.get(deck, ())
    return any(re.search(pattern, text, re.I) for pattern in patterns)


def is_about(statement, deck):
    return statement.path == "inputs/" + deck or names_deck(statement.text, deck) or \
        names_deck(statement.heading, deck)


def cost_problems(files):
    """files: {path relative to the top: text}, the pages and the decks of inputs/. One line per
    statement against the rule of the module text."""
    decks = sorted(os.path.basename(path) for path in files if path.startswith("inputs/in."))
    problems = [f"page_rules.DECK_NAMES names {deck}, which is not a deck of inputs/"
                for deck in DECK_NAMES if deck not in decks]
    statements = statements_of(files)
    marked = {deck: [] for deck in decks}
    for statement in statements:
        for deck in statement.markers:
            if deck not in marked:
                problems.append(f"{statement.where()}: the cost marker names {deck}, which is not a deck of inputs/")
            elif not statement.gives_cpu_time():
                problems.append(f"{statement.where()}: the cost marker of {deck} marks a statement that gives "
                                "no CPU time (put it inside the statement it marks)")
            else:
                marked[deck].append(statement)
    for deck, where in marked.items():
        if len(where) > 1:
            problems.append(f"the cost of {deck} is marked {len(where)} times: "
                            f"{', '.join(s.where() for s in where)}; state it once and link to it")
    for statement in statements:
        if not statement.gives_cpu_time():
            continue
        for deck in decks:
            if deck in statement.markers or not is_about(statement, deck):
                continue
            home = marked[deck][0].where() if marked[deck] else f"none is marked `cost: {deck}`"
            problems.append(f"{statement.where()}: a CPU time of {deck} outside its cost statement ({home}); "
                            f"link to it or give the cost relative to it: ...{statement.excerpt()}...")
    return problems
