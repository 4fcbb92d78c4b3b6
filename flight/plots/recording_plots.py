"""Plots of vegstream recordings (flight/plots/README in flight/README.md).

Embedded into the vegstream executable at build time and run by `vegstream report` /
`vegstream compare` as `python3 SCRIPT report DIR` or `python3 SCRIPT compare DIR_A DIR_B OUT.png`.
`python3 SCRIPT series DIR` prints the stacked series frame_time.png would draw for DIR's
frames.csv, one `panel<TAB>column<TAB>legend` line each, and draws nothing (the tests read it).
Reads frames.csv (empty cell = figure does not exist) and summary.json; writes PNGs atomically.
Exit codes: 0 done, 3 matplotlib cannot be imported, 2 bad arguments/input, 1 anything else.
"""
import csv
import json
import math
import os
import sys

# GPU passes that draw or prepare vegetation; every other pass but the simulation's is the
# non-vegetation share.
VEGETATION_PASSES = ("classify", "blades", "grass", "gravel", "trees", "plants", "vegetation", "plant_shadows")
# The shared simulation's GPU pass (issue 19: wind grid and interaction field): its own band, as
# it moves the plants but draws nothing.
SIMULATION_PASSES = ("simulation",)
# The CPU stages of a frame are the columns cpu_<stage>_ms but cpu_frame_ms (their sum), in file
# order, bottom first — the stages' own declarations (scene/frame_figures.h); those empty
# (cpu_simulation_ms while the simulation is off, cpu_seeding_ms without plants) are left out.
# Their legend labels and colours; a stage not named here shows its column's name. The
# simulation is purple in both panels.
CPU_STAGE_STYLES = {
    "cpu_flight_ms": ("flight path", "tab:gray"),
    "cpu_streaming_ms": ("streaming", "tab:orange"),
    "cpu_terrain_ms": ("terrain (tiles, ROAM)", "tab:blue"),
    "cpu_seeding_ms": ("seeding", "tab:green"),
    "cpu_simulation_ms": ("simulation (wind, grass)", "tab:purple"),
    "cpu_record_submit_ms": ("record + submit", "tab:brown"),
}
# Geometric-load columns, in legend order; those absent or empty are skipped.
GEOMETRY_COLUMNS = (
    ("terrain_triangles", "terrain triangles submitted"),
    ("terrain_leaves", "ROAM mesh triangles (leaves, culled ones too)"),
    ("terrain_seed_triangles", "seed triangles (where plants grow)"),
    ("stat_input_primitives", "input primitives (pipeline statistics)"),
    ("stat_clipping_primitives", "primitives after clipping (pipeline statistics)"),
    ("plant_clusters", "clusters submitted (species lookups)"),
    ("plant_groups", "clusters drawn (bare soil rejected)"),
    ("plants", "plants"),
    ("plant_triangles", "plant triangles (shadows included)"),
)


def fail(message, code=2):
    sys.stderr.write("plots: " + message + "\n")
    sys.exit(code)


try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # silent: vegstream tries the next interpreter or says what is missing
    sys.exit(3)


def read_frames(directory):
    path = os.path.join(directory, "frames.csv")
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail("%s: %s" % (path, e.strerror))
    if len(rows) < 2:
        fail("%s: no frames" % path)
    header, body = rows[0], rows[1:]
    cols = {name: [] for name in header}
    for row in body:
        for name, cell in zip(header, row):
            cols[name].append(float(cell) if cell != "" else math.nan)
    return cols


def read_summary(directory):
    path = os.path.join(directory, "summary.json")
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail("%s: %s" % (path, e))


def present(cols, name):
    return name in cols and any(not math.isnan(v) for v in cols[name])


def save(fig, path):
    tmp = os.path.join(os.path.dirname(path) or ".", "." + os.path.basename(path) + ".tmp")
    fig.savefig(tmp, format="png", dpi=110)
    plt.close(fig)
    os.replace(tmp, path)


def title_of(summary):
    rec = summary.get("recording", {})
    size = rec.get("size", ["?", "?"])
    return "%s over %s: %sx%s, MSAA %s, %s fps — %s" % (
        rec.get("path", {}).get("name", "?"), rec.get("dataset", {}).get("name", "?"), size[0], size[1],
        rec.get("msaa", "?"), rec.get("fps", "?"), rec.get("device", {}).get("name", "?"))


def height_panel(ax, cols):
    ax.plot(cols["t_s"], cols["height_above_ground_m"], color="0.35", lw=1)
    ax.set_ylabel("height above\nground (m)")
    ax.set_yscale("symlog", linthresh=20)
    ax.grid(alpha=0.3)


def cpu_stage_style(column):
    return CPU_STAGE_STYLES.get(column, (column[len("cpu_"):-len("_ms")], "tab:olive"))


def cpu_stage_columns(cols):
    return [c for c in cols if c.startswith("cpu_") and c.endswith("_ms") and c != "cpu_frame_ms" and present(cols, c)]


def pass_columns(cols, passes):
    return [c for c in cols if c.startswith("gpu_") and c[4:-3] in passes and present(cols, c)]


def frame_time_series(cols):
    """The stacked series of frame_time.png: {"gpu": [(column, label)], "cpu": [...]}, bottom first.

    GPU: the frame less the named passes (a computed band, column "gpu_frame_ms"), the simulation
    pass, the vegetation passes; per-pass bands only where the recording has per-pass times (empty
    on a CPU rasteriser). CPU: every stage that exists.
    """
    sim, veg = pass_columns(cols, SIMULATION_PASSES), pass_columns(cols, VEGETATION_PASSES)
    label = "non-vegetation share (terrain, sky)"
    if not veg and not sim:
        label = "the whole GPU frame (no per-pass times to split it)"
    gpu = [("gpu_frame_ms", label)]
    gpu += [(c, "simulation pass (wind, grass)") for c in sim]
    if veg:
        gpu.append(("+".join(veg), "vegetation passes"))
    cpu = [(name, cpu_stage_style(name)[0]) for name in cpu_stage_columns(cols)]
    return {"gpu": gpu, "cpu": cpu}


def column_sum(cols, names, n):
    return [sum(0.0 if math.isnan(cols[c][i]) else cols[c][i] for c in names) for i in range(n)]


def plot_frame_time(directory, cols, summary):
    t = cols["t_s"]
    n = len(t)
    gpu = cols["gpu_frame_ms"]
    series = frame_time_series(cols)
    # The GPU bands: the named passes as measured, the rest of the frame below them.
    bands = []
    for column, label in series["gpu"][1:]:
        bands.append((column_sum(cols, column.split("+"), n), label))
    named = [sum(b[0][i] for b in bands) for i in range(n)]
    rest = [max(g - v, 0.0) if not math.isnan(g) else math.nan for g, v in zip(gpu, named)]
    fig, (top, ax, cpu_ax) = plt.subplots(3, 1, figsize=(10, 8), sharex=True,
                                          gridspec_kw={"height_ratios": [1, 3, 2]})
    height_panel(top, cols)
    top.set_title(title_of(summary), fontsize=9)
    colours = {"simulation pass (wind, grass)": "tab:purple", "vegetation passes": "tab:green"}
    ax.fill_between(t, 0, rest, color="tab:blue", alpha=0.25, lw=0, label=series["gpu"][0][1])
    base = rest
    for values, label in bands:
        top_of = [b + v for b, v in zip(base, values)]
        ax.fill_between(t, base, top_of, color=colours.get(label, "tab:gray"), alpha=0.3, lw=0, label=label)
        base = top_of
    ax.plot(t, gpu, color="tab:blue", lw=1, label="GPU frame (first to last timestamp)")
    if present(cols, "cpu_frame_ms"):
        ax.plot(t, cols["cpu_frame_ms"], color="tab:orange", lw=1, label="CPU frame (sum of the stages that exist)")
    ax.plot(t, cols["wall_ms"], color="0.4", lw=0.8, ls=":", label="wall time of the frame")
    hitches = summary.get("hitches", {}).get("frames", [])
    if hitches:
        ax.scatter([t[i] for i in hitches], [gpu[i] for i in hitches], color="tab:red", s=12, zorder=3,
                   label="hitch (%d)" % len(hitches))
    if not summary.get("recording", {}).get("per_pass_gpu_times_meaningful", True):
        fig.text(0.01, 0.01, "CPU rasteriser: per-pass GPU times are not meaningful; shares come from frame totals",
                 fontsize=8, color="0.3")
    ax.set_ylabel("frame time (ms)")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    # The CPU stages stacked: which stage a CPU-bound frame spends its time in.
    if series["cpu"]:
        colour = {name: cpu_stage_style(name)[1] for name, _ in series["cpu"]}
        stages = [[0.0 if math.isnan(v) else v for v in cols[c]] for c, _ in series["cpu"]]
        cpu_ax.stackplot(t, *stages, labels=[label for _, label in series["cpu"]],
                         colors=[colour[c] for c, _ in series["cpu"]], alpha=0.5)
        # Head room above the tallest stack for the legend.
        cpu_ax.set_ylim(0, max(max(map(sum, zip(*stages))), 1e-3) * 1.6)
        cpu_ax.legend(fontsize=7, loc="upper left", ncol=3)
    cpu_ax.set_xlabel("flight time (s)")
    cpu_ax.set_ylabel("CPU stages (ms)")
    cpu_ax.grid(alpha=0.3)
    save(fig, os.path.join(directory, "frame_time.png"))


def plot_geometry(directory, cols, summary):
    t = cols["t_s"]
    fig, (top, ax) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, gridspec_kw={"height_ratios": [1, 3]})
    height_panel(top, cols)
    top.set_title(title_of(summary), fontsize=9)
    drawn = 0
    for name, label in GEOMETRY_COLUMNS:
        if present(cols, name):
            ax.plot(t, cols[name], lw=1, label=label)
            drawn += 1
    if present(cols, "stat_fragment_invocations"):
        ax2 = ax.twinx()
        ax2.plot(t, cols["stat_fragment_invocations"], color="0.5", lw=0.8, ls="--",
                 label="fragment invocations (right axis)")
        ax2.set_ylabel("fragment invocations")
        ax2.legend(fontsize=8, loc="upper right")
    ax.set_xlabel("flight time (s)")
    ax.set_ylabel("primitives per frame")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    if drawn:
        ax.legend(fontsize=8, loc="upper left")
    save(fig, os.path.join(directory, "geometric_load.png"))


def plot_streaming(directory, cols, summary):
    t = cols["t_s"]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    ax1.set_title(title_of(summary), fontsize=9)
    if present(cols, "cpu_streaming_ms"):
        ax1.plot(t, cols["cpu_streaming_ms"], lw=1, label="CPU streaming (ms)")
        ax1.legend(fontsize=8)
    else:
        ax1.text(0.5, 0.5, "no streaming yet (issue 5): the whole dataset is loaded when the scene opens",
                 transform=ax1.transAxes, ha="center", va="center", fontsize=9, color="0.3")
    ax1.set_ylabel("streaming")
    ax1.grid(alpha=0.3)
    mib = 1.0 / (1024.0 * 1024.0)
    for name, label in (("cpu_bytes", "resident on the CPU (scene)"), ("gpu_bytes", "resident on the GPU (scene)")):
        if present(cols, name):
            ax2.plot(t, [v * mib for v in cols[name]], lw=1.2, label=label)
    rss = summary.get("peak_memory", {}).get("rss_hwm_bytes", 0)
    if rss:
        ax2.axhline(rss * mib, color="0.4", ls="--", lw=0.8, label="peak RSS of the process (VmHWM)")
    ax2.set_xlabel("flight time (s)")
    ax2.set_ylabel("MiB")
    ax2.set_ylim(bottom=0)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    save(fig, os.path.join(directory, "streaming_memory.png"))


def frame_ms(cols):
    return [(0.0 if math.isnan(c) else c) + (0.0 if math.isnan(g) else g)
            for c, g in zip(cols["cpu_frame_ms"], cols["gpu_frame_ms"])]


def compare(dir_a, dir_b, out):
    ca, cb = read_frames(dir_a), read_frames(dir_b)
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True)
    name_a = os.path.basename(os.path.normpath(dir_a)) or dir_a
    name_b = os.path.basename(os.path.normpath(dir_b)) or dir_b
    ax1.plot(ca["t_s"], frame_ms(ca), lw=1, label="A: " + name_a)
    ax1.plot(cb["t_s"], frame_ms(cb), lw=1, label="B: " + name_b, alpha=0.8)
    ax1.set_ylabel("CPU + GPU frame (ms)")
    ax1.set_ylim(bottom=0)
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=8)
    for cols, label in ((ca, "A"), (cb, "B")):
        if present(cols, "terrain_triangles"):
            ax2.plot(cols["t_s"], cols["terrain_triangles"], lw=1, label=label + ": terrain triangles")
    ax2.set_xlabel("flight time (s)")
    ax2.set_ylabel("primitives per frame")
    ax2.set_ylim(bottom=0)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    save(fig, out)


def main(argv):
    if len(argv) == 3 and argv[1] == "report":
        cols, summary = read_frames(argv[2]), read_summary(argv[2])
        plot_frame_time(argv[2], cols, summary)
        plot_geometry(argv[2], cols, summary)
        plot_streaming(argv[2], cols, summary)
    elif len(argv) == 3 and argv[1] == "series":
        series = frame_time_series(read_frames(argv[2]))
        for panel in ("gpu", "cpu"):
            for column, label in series[panel]:
                print("%s\t%s\t%s" % (panel, column, label))
    elif len(argv) == 5 and argv[1] == "compare":
        compare(argv[2], argv[3], argv[4])
    else:
        fail("usage: recording_plots.py report DIR | series DIR | compare DIR_A DIR_B OUT.png")


if __name__ == "__main__":
    main(sys.argv)
