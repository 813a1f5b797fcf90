#!/usr/bin/env python3
"""Compares every number of two compare report.json files, times and the run's own facts aside.

usage: bench/report_numbers.py A/report.json B/report.json [--rel 1e-9]
Prints how many numbers there are, how many differ beyond the relative tolerance, and the largest
differences; exits 1 if any differ (0 otherwise).
"""
import json
import sys


def numbers(node, at, out):
    if isinstance(node, dict):
        for k, v in node.items():
            if "ms" in k or k in ("run", "date", "times"):
                continue
            numbers(v, at + "/" + k, out)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            numbers(v, at + "/" + str(i), out)
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        out[at] = float(node)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    rel = 1e-9
    if "--rel" in sys.argv:
        rel = float(sys.argv[sys.argv.index("--rel") + 1])
        args = [a for a in args if a != str(sys.argv[sys.argv.index("--rel") + 1])]
    if len(args) != 2:
        sys.exit("usage: report_numbers.py A/report.json B/report.json [--rel X]")
    a, b = {}, {}
    numbers(json.load(open(args[0])), "", a)
    numbers(json.load(open(args[1])), "", b)
    if a.keys() != b.keys():
        only = sorted(set(a) ^ set(b))
        print(f"the reports hold different numbers: {len(only)} paths in one only, e.g. {only[:3]}")
        sys.exit(1)
    differ = []
    for k, x in a.items():
        y = b[k]
        if x != y and abs(x - y) > rel * max(1.0, abs(x)):
            differ.append((abs(x - y) / max(1e-300, abs(x)), k, x, y))
    print(f"{len(a)} numbers, {len(differ)} differ beyond {rel:g} relative")
    for d in sorted(differ, reverse=True)[:10]:
        print(f"  {d[1]}: {d[2]!r} vs {d[3]!r} ({d[0]:.3g} relative)")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
