"""Readers of the LAMMPS files the decks write: fix ave/time and fix ave/chunk files, and dumps
(plain or gzip, a gzip stream cut by a kill included).

Two views of each file: records, the text of each time step as written (to splice the legs of a
run), and rows, the values by column name (to analyse them). A block or frame cut by a kill is
left out of the records; the row readers refuse a malformed file with its name and line.
"""

import gzip
import os
import zlib


class FileFormatError(RuntimeError):
    """A file that is not what its reader expects; the message names the file."""


def _column_names(header_line):
    """'# TimeStep v_time ...' -> ['TimeStep', 'v_time', ...]."""
    return header_line[1:].split()


# ---------------------------------------------------------------------------------------
# fix ave/time
# ---------------------------------------------------------------------------------------

def read_time_file(path):
    """fix ave/time file -> [{column: value}], the columns named by the last '#' line before
    each row."""
    names, rows = None, []
    with open(path) as src:
        for number, line in enumerate(src, 1):
            if line.startswith("#"):
                names = _column_names(line)
                continue
            fields = line.split()
            if not fields:
                continue
            if names is None or len(fields) != len(names):
                raise FileFormatError(f"{path}:{number}: {len(fields)} values under a header of "
                                      f"{len(names or [])} columns")
            try:
                rows.append(dict(zip(names, map(float, fields))))
            except ValueError:
                raise FileFormatError(f"{path}:{number}: not a row of numbers under its header") from None
    return rows


def read_time_records(path):
    """fix ave/time file -> (header lines, [(timestep, line)])."""
    header, records = [], []
    with open(path) as src:
        for line in src:
            if line.startswith("#"):
                if not records:
                    header.append(line)
                continue
            fields = line.split()
            if fields:
                records.append((int(float(fields[0])), line))
    return header, records


def time_span(path, column="v_time"):
    """(first, last) value of `column` in a fix ave/time file still being written, or None
    before its first row. Only the head and the tail are read; a row cut by a kill is skipped."""
    try:
        with open(path, "rb") as src:
            head = src.read(8192).decode(errors="replace").splitlines()
            src.seek(max(0, os.path.getsize(path) - 8192))
            tail = src.read().decode(errors="replace").splitlines()
    except OSError:
        return None
    names = [_column_names(line) for line in head if line.startswith("#")]
    if not names or column not in names[-1]:
        return None
    index, width = names[-1].index(column), len(names[-1])

    def value_of(line):
        fields = line.split()
        if line.startswith("#") or len(fields) != width:
            return None
        try:
            return float(fields[index])
        except ValueError:
            return None
    firsts = [t for t in map(value_of, head) if t is not None]
    lasts = [t for t in map(value_of, tail[1:]) if t is not None]    # tail[0] may be cut
    if not firsts:
        return None
    return firsts[0], (lasts[-1] if lasts else firsts[-1])


# ---------------------------------------------------------------------------------------
# fix ave/chunk
# ---------------------------------------------------------------------------------------

def _chunk_blocks(path):
    """(header lines, [(timestep, block lines)], whether the last block was cut). A block is
    its 'step count total' line and one line per chunk."""
    header, blocks = [], []
    block, step, remaining = [], None, 0
    with open(path) as src:
        for line in src:
            if line.startswith("#"):
                if not blocks and step is None:
                    header.append(line)
                continue
            if not line.strip():
                continue
            if remaining == 0:
                fields = line.split()
                step, remaining = int(float(fields[0])), int(float(fields[1]))
                block = [line]
            else:
                block.append(line)
                remaining -= 1
            if remaining == 0:
                blocks.append((step, block))
    return header, blocks, remaining > 0


def read_chunk_records(path):
    """fix ave/chunk file -> (header lines, [(timestep, block text)]); a block cut by a kill is
    dropped."""
    header, blocks, _ = _chunk_blocks(path)
    return header, [(step, "".join(lines)) for step, lines in blocks]


def read_chunk_file(path):
    """fix ave/chunk file -> [(timestep, [{column: value}, one per chunk])], the columns named
    by its last header line."""
    header, blocks, cut = _chunk_blocks(path)
    if cut:
        raise FileFormatError(f"{path}: the block after step {blocks[-1][0] if blocks else '-'} is cut")
    if not header:
        raise FileFormatError(f"{path}: no header naming the columns")
    names = _column_names(header[-1])
    return [(step, [dict(zip(names, map(float, line.split()))) for line in lines[1:]])
            for step, lines in blocks]


# ---------------------------------------------------------------------------------------
# Dumps
# ---------------------------------------------------------------------------------------

def _read_truncated_gzip(path):
    """The text of every gzip member of a file, up to where a kill cut it."""
    out = []
    decompressor = zlib.decompressobj(16 + zlib.MAX_WBITS)
    with open(path, "rb") as src:
        data = src.read()
    while data:
        try:
            out.append(decompressor.decompress(data))
        except zlib.error:
            break
        data = decompressor.unused_data
        if data:
            decompressor = zlib.decompressobj(16 + zlib.MAX_WBITS)
    return b"".join(out).decode(errors="replace")


def _dump_text(path):
    if not path.endswith(".gz"):
        with open(path) as src:
            return src.read()
    try:
        with gzip.open(path, "rt") as src:
            return src.read()
    except (OSError, EOFError):
        return _read_truncated_gzip(path)


def _item(lines, name):
    """Index of the line 'ITEM: name...' of a frame, or None."""
    return next((i for i, line in enumerate(lines) if line.startswith("ITEM: " + name)), None)


def _dump_frames(path):
    """[(timestep, frame lines)]: the complete frames of a dump, each from the line after
    'ITEM: TIMESTEP' to its last atom."""
    text = _dump_text(path)
    if not text.endswith("\n"):
        text = text[:text.rfind("\n") + 1]    # the last line was cut
    frames = []
    for frame in text.split("ITEM: TIMESTEP\n")[1:]:
        lines = frame.split("\n")
        try:
            step = int(lines[0])
            count = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
        except (ValueError, IndexError):
            continue
        start = _item(lines, "ATOMS")
        if start is None:
            continue
        atoms = [line for line in lines[start + 1:] if line.strip()]
        if len(atoms) == count:
            frames.append((step, lines[:start + 1] + atoms))
    return frames


def read_dump_records(path):
    """Dump -> ([], [(timestep, frame text)]), complete frames only."""
    return [], [(step, "ITEM: TIMESTEP\n" + "\n".join(lines) + "\n") for step, lines in _dump_frames(path)]


def read_dump(path):
    """Complete frames of a dump: [(timestep, box, {id: {column: value}})], box the (lo, hi) of
    each axis (None without BOX BOUNDS)."""
    frames = []
    for step, lines in _dump_frames(path):
        bounds = _item(lines, "BOX BOUNDS")
        box = None if bounds is None else [tuple(map(float, line.split()[:2])) for line in lines[bounds + 1:bounds + 4]]
        start = _item(lines, "ATOMS")
        columns = lines[start].split()[2:]
        atoms = {}
        for line in lines[start + 1:]:
            fields = line.split()
            if len(fields) != len(columns):
                raise FileFormatError(f"{path}: step {step}: the row '{line}' does not match {columns}")
            values = dict(zip(columns, map(float, fields)))
            atoms[int(values["id"])] = values
        frames.append((step, box, atoms))
    return frames


def unwrapped(frame):
    """{id: (x, y)} of a dump frame with x unwrapped through the periodic image count ix."""
    _, box, atoms = frame
    length = box[0][1] - box[0][0]
    return {i: (a["x"] + a["ix"] * length, a["y"]) for i, a in atoms.items()}
