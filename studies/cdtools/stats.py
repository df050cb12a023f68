"""Statistics of replicas and series: means with their scatter and standard error, a standard
deviation pooled over groups, differences in units of their error, a least-squares slope."""

import math
import statistics


def mean_sd_se(values):
    """Mean, standard deviation and standard error of the mean; nan where fewer values than
    they need (the mean of one value is that value)."""
    values = list(values)
    if len(values) < 2:
        return (values[0] if values else math.nan), math.nan, math.nan
    sd = statistics.stdev(values)
    return statistics.mean(values), sd, sd / math.sqrt(len(values))


def pooled_sd(groups):
    """Standard deviation pooled over groups, each about its own mean (nan without a group of
    two)."""
    squares = sum(sum((v - sum(g) / len(g)) ** 2 for v in g) for g in groups if len(g) > 1)
    freedom = sum(len(g) - 1 for g in groups if len(g) > 1)
    return math.sqrt(squares / freedom) if freedom else math.nan


def difference_in_errors(x, error, x_ref, error_ref):
    """(x - x_ref) over the combined error sqrt(error^2 + error_ref^2); nan if that is 0."""
    combined = math.hypot(error, error_ref)
    return (x - x_ref) / combined if combined > 0 else math.nan


def least_squares_line(xs, ys):
    """(intercept, slope) of the unweighted least-squares line through (x, y)."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return my - slope * mx, slope


def least_squares_slope(ts, ys):
    """Slope of the least-squares line through (t, y), and its R^2 (0 for constant y)."""
    n = len(ts)
    mt, my = sum(ts) / n, sum(ys) / n
    stt = sum((t - mt) ** 2 for t in ts)
    sty = sum((t - mt) * (y - my) for t, y in zip(ts, ys))
    slope = sty / stt
    residual = sum((y - my - slope * (t - mt)) ** 2 for t, y in zip(ts, ys))
    total = sum((y - my) ** 2 for y in ys)
    return slope, 1.0 - residual / total if total > 0 else 0.0
