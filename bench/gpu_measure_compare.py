#!/usr/bin/env python3
"""bench/gpu-measure's regression guard (issue 44 item 1): two measurement directories side by side.

Usage: gpu_measure_compare.py BASE_DIR DIR. For each recording NAME in both (NAME/summary.json,
NAME/frames.csv): GPU frame, CPU frame and wall p50 / p99, then every per-pass GPU time column
(gpu_*_ms) p50 / p99, all from summary.json's times_ms (the whole flight, as report.md's tables);
then the plants drawn (median over the low phase, as report.md) and the trees drawn (full + reduced
+ impostor, median over the whole flight). Each figure as DIR's, BASE_DIR's and DIR / BASE_DIR.
A time more than 10 % above the base is marked "▲ REGRESSION", a count below it "▼ DROPPED":
figures only, the exit status is 0 whatever they say. Exit 2, with one line, when either
directory is missing or holds no recording.
"""
import csv
import json
import math
import os
import sys

from gpu_measure_report import LOW_PHASE_S, ORDER, column, fmt, median

SLOWER = 1.10  # a time ratio above this is flagged
FRAME_TIMES = ["gpu_frame_ms", "cpu_frame_ms", "wall_ms"]
TREE_LEVELS = ("trees_full", "trees_reduced", "trees_impostor")
SETTINGS = [("device", lambda r: r.get("device", {}).get("name")), ("size", lambda r: r.get("size")),
            ("MSAA", lambda r: r.get("msaa")), ("fps", lambda r: r.get("fps")),
            ("path", lambda r: r.get("path", {}).get("name"))]


def recordings(d):
    """NAME → (summary, frames.csv rows) for every NAME/summary.json in d: report order, then the rest."""
    names = sorted(n for n in os.listdir(d) if os.path.isfile(os.path.join(d, n, "summary.json")))
    names.sort(key=lambda n: ORDER.index(n) if n in ORDER else len(ORDER))
    out = {}
    for n in names:
        with open(os.path.join(d, n, "summary.json")) as f:
            s = json.load(f)
        rows = []
        if os.path.isfile(os.path.join(d, n, "frames.csv")):
            with open(os.path.join(d, n, "frames.csv"), newline="") as f:
                rows = list(csv.DictReader(f))
        out[n] = (s, rows)
    return out


def quantile(times, col, q):
    t = times.get(col)
    v = t.get(q) if t else None
    return None if v is None or (isinstance(v, float) and math.isnan(v)) else float(v)


def pass_columns(new_times, base_times):
    """The per-pass GPU columns of either side, the new side's order first."""
    cols = [c for c in list(new_times) + list(base_times)
            if c.startswith("gpu_") and c.endswith("_ms") and c != "gpu_frame_ms"]
    return list(dict.fromkeys(cols))


def time_figures(new, base):
    """(figure, new, base) for the frame times and every pass, p50 and p99."""
    tn, tb = new["times_ms"], base["times_ms"]
    cols = FRAME_TIMES + pass_columns(tn, tb)
    return [(f"{c} {q}", quantile(tn, c, q), quantile(tb, c, q)) for c in cols for q in ("p50", "p99")]


def trees_drawn(rows):
    per_frame = []
    for r in rows:
        cells = [r.get(c, "") for c in TREE_LEVELS]
        if all(v != "" for v in cells):
            per_frame.append(sum(float(v) for v in cells))
    return median(per_frame)


def count_figures(new_rows, base_rows):
    """(figure, new, base) for the plants and trees drawn, where either side has them."""
    lo, hi = LOW_PHASE_S
    out = [(f"plants (t {lo:g}–{hi:g} s, median)", median(column(new_rows, "plants", True)),
            median(column(base_rows, "plants", True))),
           ("trees drawn (median)", trees_drawn(new_rows), trees_drawn(base_rows))]
    return [f for f in out if f[1] is not None or f[2] is not None]


def ratio_cell(new, base, is_time):
    if new is None or base is None or base == 0:
        return "—", False
    r = new / base
    if is_time and r > SLOWER:
        return f"**{r:.2f} ▲ REGRESSION**", True
    if not is_time and new < base:
        return f"**{r:.2f} ▼ DROPPED**", True
    return f"{r:.2f}", False


def setting_changes(new, base):
    rn, rb = new.get("recording", {}), base.get("recording", {})
    return [f"{k} {get(rn)} (base {get(rb)})" for k, get in SETTINGS if get(rn) != get(rb)]


def recording_table(name, new, base, flagged):
    """The markdown lines of one recording's figures; appends each flagged figure to flagged."""
    (sn, rn), (sb, rb) = new, base
    lines = [f"### {name}\n"]
    changes = setting_changes(sn, sb)
    if changes:
        lines.append(f"Not measured alike: {', '.join(changes)}.\n")
    lines += ["| figure | new | base | new / base |", "|---|---|---|---|"]
    figures = [(f, n, b, True) for f, n, b in time_figures(sn, sb)]
    figures += [(f, n, b, False) for f, n, b in count_figures(rn, rb)]
    for figure, n, b, is_time in figures:
        cell, flag = ratio_cell(n, b, is_time)
        if flag:
            flagged.append(f"{name}: {figure} {cell.strip('*')}")
        lines.append(f"| {figure} | {fmt(n, 0 if not is_time else 3)} | {fmt(b, 0 if not is_time else 3)} | {cell} |")
    return lines + [""]


def compare(base_dir, new_dir):
    """The comparison as markdown lines."""
    new, base = recordings(new_dir), recordings(base_dir)
    both = [n for n in new if n in base]
    lines = [f"## Against {base_dir}\n",
             f"new = {new_dir}, base = {base_dir}; times: summary.json p50 / p99 over the whole flight; "
             f"▲ a time more than {round((SLOWER - 1) * 100)} % above the base, ▼ fewer plants or trees drawn.\n"]
    only_new, only_base = [n for n in new if n not in base], [n for n in base if n not in new]
    if only_new or only_base:
        lines.append(f"Not compared: new only {', '.join(only_new) or '—'}; base only {', '.join(only_base) or '—'}.\n")
    if not both:
        lines.append("No recording is in both directories.\n")
    flagged = []
    for n in both:
        lines += recording_table(n, new[n], base[n], flagged)
    lines.append(f"**Flagged: {len(flagged)}**" + ("" if flagged else " (no time over "
                 f"×{SLOWER:.2f}, no count lower)."))
    lines += [f"- {f}" for f in flagged]
    return lines


def check_dir(d, role):
    """None, or the one line that says why d cannot be compared."""
    if not os.path.isdir(d):
        return f"gpu_measure_compare: {role} {d}: no such directory"
    if not any(os.path.isfile(os.path.join(d, n, "summary.json")) for n in os.listdir(d)):
        return f"gpu_measure_compare: {role} {d}: no recordings there (no NAME/summary.json)"
    return None


def main(argv):
    if len(argv) != 2:
        print("usage: gpu_measure_compare.py BASE_DIR DIR", file=sys.stderr)
        return 2
    base_dir, new_dir = argv
    for d, role in ((base_dir, "base"), (new_dir, "new")):
        why = check_dir(d, role)
        if why:
            print(why, file=sys.stderr)
            return 2
    print("\n".join(compare(base_dir, new_dir)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
