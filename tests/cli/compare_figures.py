#!/usr/bin/env python3
"""Compares the figures of two compare reports (a sweep's or a single view's report.json):
every error figure of every configuration in every view, the reference's normalisation and
the sweep's per-configuration means, exactly (as JSON numbers). Timings (frameMs, its
quartiles frameMsQuartiles, passMs) and
where the reference came from (rendered or cached) are left out: they differ between any two
runs. Prints the count and each difference; exit 1 when any differs or either has none.
Usage: compare_figures.py EXPECTED_DIR ACTUAL_DIR"""
import json
import os
import sys

TIMINGS = {"frameMs", "frameMsQuartiles", "passMs"}


def view_figures(report, prefix, out):
    for p in report["paths"]:
        for name, value in p.items():
            if name not in TIMINGS:
                out[(prefix, p["path"], name)] = value
    out[(prefix, "reference", "normalisation")] = report["reference"].get("normalisation")
    out[(prefix, "reference", "meanLuminance")] = report["reference"].get("meanLuminance")


def figures(root):
    with open(os.path.join(root, "report.json")) as f:
        top = json.load(f)
    out = {}
    if top.get("kind") != "sweep":
        view_figures(top, "", out)
        return out
    for v in top["views"]:
        with open(os.path.join(root, v["report"])) as f:
            view_figures(json.load(f), v["dir"], out)
        # The top-level report's copy of the view's figures must be the view's own.
        view_figures(v, "top:" + v["dir"], out)
    for c in top["configurations"]:
        for name, value in c.items():
            if name not in TIMINGS:
                out[("means", c["path"], name)] = value
    return out


expected, actual = figures(sys.argv[1]), figures(sys.argv[2])
differ = sorted(k for k in set(expected) | set(actual) if expected.get(k, "missing") != actual.get(k, "missing"))
for k in differ:
    print("differs:", "/".join(k), expected.get(k, "missing"), actual.get(k, "missing"))
print(f"{len(expected)} figures, {len(differ)} differ")
sys.exit(1 if differ or not expected else 0)
