"""Writes the small subset of TOML a nullpath scene file needs (Blender's Python has no TOML
writer): tables of numbers, booleans, strings, arrays and inline tables."""

import json
import math


def value(v):
    """One TOML value."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"a scene file holds finite numbers only, got {v}")
        return repr(v)  # the shortest text that reads back as the same double
    if isinstance(v, str):
        return json.dumps(v)  # a JSON string is a TOML basic string
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{key(k)} = {value(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def key(k):
    """A bare key where TOML allows one, else a quoted key."""
    bare = k and all(c.isascii() and (c.isalnum() or c in "-_") for c in k)
    return k if bare else json.dumps(k)


def document(tables):
    """A TOML document: `tables` maps a table header (dotted, e.g. "lower.sky") to its key–value
    pairs; a header mapping to a list of dicts is an array of tables (`[[objects]]`)."""
    lines = []
    for header, body in tables.items():
        entries = body if isinstance(body, list) else [body]
        brackets = ("[[", "]]") if isinstance(body, list) else ("[", "]")
        for entry in entries:
            if lines:
                lines.append("")
            lines.append(f"{brackets[0]}{header}{brackets[1]}")
            lines.extend(f"{key(k)} = {value(v)}" for k, v in entry.items())
    return "\n".join(lines) + "\n"
