#!/usr/bin/env python3
"""Compares a README/docs block as written with the same block regenerated
(scripts/readme-tables.sh --check), ignoring what a machine's speed changes:

- in a Markdown table, the cells of a column whose header names a time ("time",
  "wall", "CPU", "seconds", "[s]", "(s)", "s per", "ns", "ms", "µs", "speed") or a
  ratio of times ("jointlin / ccx", "fast / linear", "modal / direct"), or a process's
  memory ("RSS", "memory": the allocator's and the BLAS threads' share varies by machine);
- elsewhere, a number followed by " s", " ms", " µs" or " ns" (a duration) or directly
  by "×" (a speed ratio).

Every other number must agree within two units of its last printed digit (a result
rounded on the other side of a digit on another machine) or 1e-9 of itself (round-off of
a number printed with more digits than it holds, e.g. an eigenfrequency to 13); every
other character must be the same. Prints each differing line and exits 1 if any.

Usage: compare-blocks.py WRITTEN REGENERATED LABEL
"""

import re
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
DURATION = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?= (?:s|ms|µs|ns)\b| (?:s|ms|µs|ns)$|×)")
TIMING_HEADER = re.compile(
    r"time|wall|cpu|seconds|\[s\]|\(s\)|\[ms\]|\bs per|\bns\b|\bms\b|µs|speed"
    r"|\w / (?:ccx|linear|direct)\b|\bRSS\b|memory",
    re.IGNORECASE,
)


def cells(line):
    """The cells of a Markdown table row, or None."""
    s = line.strip()
    if not (s.startswith("|") and s.endswith("|")):
        return None
    return [c.strip() for c in s[1:-1].split("|")]


def masked_lines(text):
    """The lines with timings replaced by "<t>"."""
    lines = text.splitlines()
    out = []
    timing_columns = set()
    for k, line in enumerate(lines):
        row = cells(line)
        if row is None:
            timing_columns = set()
            out.append(DURATION.sub("<t>", line))
            continue
        nxt = cells(lines[k + 1]) if k + 1 < len(lines) else None
        if nxt and all(re.fullmatch(r":?-+:?", c) for c in nxt):
            timing_columns = {i for i, c in enumerate(row) if TIMING_HEADER.search(c)}
        row = ["<t>" if i in timing_columns else DURATION.sub("<t>", c) for i, c in enumerate(row)]
        out.append("| " + " | ".join(row) + " |")
    return out


def last_digit(token):
    """One unit of the last printed digit of a number token."""
    mantissa, _, exponent = token.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 10.0 ** (int(exponent or 0) - decimals)


def same(a, b):
    """Whether two masked lines agree (numbers within two units of their last digit)."""
    ta, tb = NUMBER.split(a), NUMBER.split(b)
    na, nb = NUMBER.findall(a), NUMBER.findall(b)
    if ta != tb or len(na) != len(nb):
        return False
    for x, y in zip(na, nb):
        if x == y:
            continue
        unit = max(last_digit(x), last_digit(y))
        scale = max(abs(float(x)), abs(float(y)))
        if abs(float(x) - float(y)) > max(2.0 * unit * (1.0 + 1e-9), 1e-9 * scale):
            return False
    return True


def main():
    written, regenerated, label = sys.argv[1:4]
    a = masked_lines(open(written, encoding="utf-8").read())
    b = masked_lines(open(regenerated, encoding="utf-8").read())
    bad = 0
    if len(a) != len(b):
        print(f"{label}: {len(a)} lines as written, {len(b)} regenerated")
        bad = 1
    for k, (x, y) in enumerate(zip(a, b)):
        if not same(x, y):
            print(f"{label}, line {k + 1}:\n  as written:  {x}\n  regenerated: {y}")
            bad = 1
    sys.exit(bad)


if __name__ == "__main__":
    main()
