"""Shared helpers of the bench's JSON checkers (check_json.py, check_render_json.py): a list of
problems, one line each, and a typed, finite, bounded number check."""
import math

problems = []


def fail(where, message):
    problems.append(f"{where}: {message}")


def number(obj, key, where, minimum=None, maximum=None, integral=False):
    """obj[key] as a finite number (an integer when integral) within [minimum, maximum], or None
    after recording why not."""
    if key not in obj:
        fail(where, f"missing '{key}'")
        return None
    v = obj[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or (integral and not isinstance(v, int)):
        fail(where, f"'{key}' is {v!r}, expected {'an integer' if integral else 'a number'}")
        return None
    if not math.isfinite(v):
        fail(where, f"'{key}' is not finite")
        return None
    if minimum is not None and v < minimum:
        fail(where, f"'{key}' = {v} < {minimum}")
    if maximum is not None and v > maximum:
        fail(where, f"'{key}' = {v} > {maximum}")
    return v
