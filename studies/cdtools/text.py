"""Text of the tools' tables and messages: numbers, values with their error, parameter values
in names and -var arguments, durations, Markdown tables."""

import math


def number(value, digits=3):
    """value to `digits` significant digits; '–' for None, nan or inf."""
    if value is None or not math.isfinite(value):
        return "–"
    return f"{value:.{digits}g}"


def with_error(value, error):
    """'value ± error' with the error to two significant digits (the value to four without one)."""
    if error is None or error <= 0:
        return number(value, 4)
    places = max(0, 1 - int(math.floor(math.log10(error))))
    return f"{value:.{places}f} ± {error:.{places}f}" if places < 8 else f"{value:.3g} ± {error:.2g}"


def parameter(value):
    """Short, stable text of a parameter value in names and -var arguments (2.0 -> '2')."""
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    return str(value)


def duration(seconds):
    """'1d02h', '3h05m' or '4m07s'; '?' if unknown."""
    if seconds is None or not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    days, rest = divmod(seconds, 86400)
    hours, rest = divmod(rest, 3600)
    minutes, secs = divmod(rest, 60)
    if days:
        return f"{days}d{hours:02d}h"
    if hours:
        return f"{hours}h{minutes:02d}m"
    return f"{minutes}m{secs:02d}s"


def markdown_table(headings, rows):
    lines = ["| " + " | ".join(headings) + " |", "|" + "---|" * len(headings)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"
