#!/usr/bin/env python3
"""bench/gpu-measure's report: one markdown document from the recordings and bench JSON in DIR.

Usage: gpu_measure_report.py DIR [FAILED_NAME ...]. Tables: the frame per recording (GPU, CPU and
wall p50/p99, plants in the low phase), GPU ms per pass (p50/p99; empty where the device's
per-pass times mean nothing), the Hi-Z occlusion culling (median per frame over the whole flight:
seed triangles tested and culled, plants classified and culled; canyon vs canyon-no-cull is the
comparison), CPU ms per stage and ROAM ms per phase, and every benchmark with its counters.
"""
import csv
import json
import math
import os
import re
import statistics
import sys

ORDER = ["default", "no-plants", "forward", "forward-no-plants", "deferred", "dense-deferred", "compute", "compute-no-plants", "dense-compute", "canyon-compute", "kolob-forest-compute", "dense", "dense-serial", "tessellation", "dense-tessellation", "canyon", "canyon-no-cull", "canyon-dense", "slickrock", "wind", "dense-wind", "wind-tessellation", "meadow-wind", "kolob-forest", "kolob-forest-no-trees", "kolob-forest-no-shadows", "kolob-forest-no-cores", "gallery-meadow", "gallery-forest-edge", "gallery-slickrock", "gallery-overview"]
LOW_PHASE_S = (10.0, 20.0)  # benchmark-30s: near the ground between 10 and 20 s


def fmt(v, digits=2):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    if isinstance(v, float):
        return f"{v:.{digits}f}"
    return str(v)


def pct(times, column, q):
    t = times.get(column)
    return None if not t else t.get(q)


def column(rows, name, low_phase=False):
    out = []
    for r in rows:
        if low_phase and not (LOW_PHASE_S[0] <= float(r["t_s"]) <= LOW_PHASE_S[1]):
            continue
        if r.get(name, "") != "":
            out.append(float(r[name]))
    return out


def median(values):
    return statistics.median(values) if values else None


def main():
    d = sys.argv[1]
    failed = sys.argv[2:]
    recordings = [n for n in ORDER if os.path.isfile(os.path.join(d, n, "summary.json"))]
    print("# gpu-measure report\n")
    if failed:
        print(f"**Failed:** {', '.join(failed)} (their logs are in the directory).\n")
    if recordings:
        first = json.load(open(os.path.join(d, recordings[0], "summary.json")))["recording"]
        dev = first["device"]
        print(f"Device: {dev['name']} ({dev['driver']}), {first['size'][0]}×{first['size'][1]}, "
              f"MSAA {first['msaa']}, {first['fps']} fps, per-pass GPU times "
              f"{'meaningful' if first['per_pass_gpu_times_meaningful'] else 'not meaningful (CPU rasteriser)'}.\n")
        print("## Frames\n")
        print("| recording | path | frames | in flight | GPU p50 / p99 ms | CPU p50 / p99 ms | wall p50 / p99 ms | "
              "plants (low phase, median) | plant triangles (low phase) | terrain triangles (median) |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        passes = []
        data = {}
        for n in recordings:
            s = json.load(open(os.path.join(d, n, "summary.json")))
            rows = list(csv.DictReader(open(os.path.join(d, n, "frames.csv"))))
            data[n] = (s, rows)
            t = s["times_ms"]
            for p in s["recording"].get("gpu_passes", []):
                if p not in passes:
                    passes.append(p)
            # A recording at another fps than the first (--only NAME:FPS) says so.
            fps = s["recording"].get("fps")
            at = f" ({fps} fps)" if fps != first["fps"] else ""
            # Recordings made before --frames-in-flight ran one frame at a time.
            print(f"| {n} | {s['recording']['path']['name']}{at} | {s['frames']} | "
                  f"{s['recording'].get('frames_in_flight', 1)} | "
                  f"{fmt(pct(t, 'gpu_frame_ms', 'p50'))} / {fmt(pct(t, 'gpu_frame_ms', 'p99'))} | "
                  f"{fmt(pct(t, 'cpu_frame_ms', 'p50'))} / {fmt(pct(t, 'cpu_frame_ms', 'p99'))} | "
                  f"{fmt(pct(t, 'wall_ms', 'p50'))} / {fmt(pct(t, 'wall_ms', 'p99'))} | "
                  f"{fmt(median(column(rows, 'plants', True)), 0)} | "
                  f"{fmt(median(column(rows, 'plant_triangles', True)), 0)} | "
                  f"{fmt(median(column(rows, 'terrain_triangles')), 0)} |")
        print("\n## GPU ms per pass (p50 / p99)\n")
        print("| recording | " + " | ".join(passes) + " |")
        print("|---|" + "---|" * len(passes))
        for n in recordings:
            t = data[n][0]["times_ms"]
            cells = []
            for p in passes:
                c = "gpu_" + "".join(ch if ch.isalnum() else "_" for ch in p.lower()) + "_ms"
                cells.append(f"{fmt(pct(t, c, 'p50'))} / {fmt(pct(t, c, 'p99'))}")
            print(f"| {n} | " + " | ".join(cells) + " |")
        print("\n## Occlusion culling (median per frame, whole flight)\n")
        print("| recording | seed triangles tested | culled | plants classified | plants culled | "
              "plant triangles | GPU frame p50 ms |")
        print("|---|---|---|---|---|---|---|")
        for n in recordings:
            s, rows = data[n]
            print(f"| {n} | {fmt(median(column(rows, 'plant_cull_tested')), 0)} | "
                  f"{fmt(median(column(rows, 'plant_cull_culled')), 0)} | "
                  f"{fmt(median(column(rows, 'plants')), 0)} | "
                  f"{fmt(median(column(rows, 'plants_culled')), 0)} | "
                  f"{fmt(median(column(rows, 'plant_triangles')), 0)} | "
                  f"{fmt(pct(s['times_ms'], 'gpu_frame_ms', 'p50'))} |")
        print("\n## Trees (issue 20; median per frame, whole flight)\n")
        print("| recording | full | reduced | impostor | dropped | trees in pages | tiles drawn / wanted | "
              "budget bound (frames) | tree GPU MB | GPU frame p50 / p99 ms |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        for n in recordings:
            s, rows = data[n]
            if not column(rows, "trees_classified"):
                continue
            bound = sum(1 for v in column(rows, "tree_budget_bound") if v > 0)
            mb = median(column(rows, "tree_gpu_bytes"))
            print(f"| {n} | {fmt(median(column(rows, 'trees_full')), 0)} | "
                  f"{fmt(median(column(rows, 'trees_reduced')), 0)} | "
                  f"{fmt(median(column(rows, 'trees_impostor')), 0)} | "
                  f"{fmt(median(column(rows, 'trees_dropped')), 0)} | "
                  f"{fmt(median(column(rows, 'trees_classified')), 0)} | "
                  f"{fmt(median(column(rows, 'tree_tiles_drawn')), 0)} / {fmt(median(column(rows, 'tree_tiles_wanted')), 0)} | "
                  f"{bound} | {fmt(mb / 1048576.0 if mb is not None else None, 1)} | "
                  f"{fmt(pct(s['times_ms'], 'gpu_frame_ms', 'p50'))} / {fmt(pct(s['times_ms'], 'gpu_frame_ms', 'p99'))} |")
        print("\n## CPU ms per stage (p50 / p99)\n")
        stages = ["cpu_streaming_ms", "cpu_terrain_ms", "cpu_seeding_ms", "cpu_record_submit_ms", "cpu_frame_ms"]
        print("| recording | " + " | ".join(stages) + " |")
        print("|---|" + "---|" * len(stages))
        for n in recordings:
            t = data[n][0]["times_ms"]
            print(f"| {n} | " + " | ".join(f"{fmt(pct(t, c, 'p50'))} / {fmt(pct(t, c, 'p99'))}" for c in stages) + " |")
        # Where cpu_terrain_ms goes: the update's priority traversal (on the workers too) and split
        # queue (the frame thread alone), the output, and the wait for the last compaction's copy.
        print("\n## ROAM ms per phase (p50 / p99)\n")
        phases = ["terrain_roam_update_ms", "terrain_roam_priorities_ms", "terrain_roam_split_ms",
                  "terrain_roam_compact_wait_ms", "terrain_roam_output_ms"]
        print("| recording | " + " | ".join(phases) + " |")
        print("|---|" + "---|" * len(phases))
        for n in recordings:
            t = data[n][0]["times_ms"]
            print(f"| {n} | " + " | ".join(f"{fmt(pct(t, c, 'p50'))} / {fmt(pct(t, c, 'p99'))}" for c in phases) + " |")
    for bench in ("bench_plants", "bench_roam"):
        f = os.path.join(d, bench + ".json")
        if not os.path.isfile(f):
            continue
        b = json.load(open(f))
        print(f"\n## {bench}\n")
        print("| benchmark | real time | counters |")
        print("|---|---|---|")
        for r in b.get("benchmarks", []):
            skip = {"name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
                    "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit"}
            counters = ", ".join(f"{k} {fmt(v) if isinstance(v, float) else v}" for k, v in r.items() if k not in skip)
            print(f"| {r['name']} | {fmt(r.get('real_time'))} {r.get('time_unit', '')} | {counters} |")
        if bench == "bench_plants":
            plants_ratios(b.get("benchmarks", []))
    return 0


def plants_ratios(benchmarks):
    """Each bench_plants case's vegetation cost (case − terrain only) against the speed of light's,
    and the blade rate: the figure issue 17 asks for, from one run (cases: bench/bench_plants.cpp)."""
    names = {0: "terrain only", 1: "tessellation", 2: "tessellation, no shadows", 3: "speed of light",
             4: "compute", 5: "compute, no shadows", 6: "terrain + simulation (8 m/s wind)",
             7: "tessellation, no shadows, wind", 8: "compute, no shadows, wind"}
    ms, blades = {}, {}
    for r in benchmarks:
        m = re.search(r"case:(\d+)", r["name"])
        if r.get("run_type", "iteration") != "iteration" or not m:
            continue
        c = int(m.group(1))
        ms[c] = r["real_time"]
        blades[c] = r.get("plants")
    if 0 not in ms or 3 not in ms or ms[3] <= ms[0]:
        return
    print("\n| bench_plants case | vegetation ms (case − terrain; wind cases − terrain + simulation) | × speed of light | M blades / s |")
    print("|---|---|---|---|")
    for c in sorted(ms):
        if c == 0:
            continue
        # The wind cases' plants against terrain + simulation (case 6); case 6 against the terrain.
        veg = ms[c] - (ms[6] if c in (7, 8) and 6 in ms else ms[0])
        rate = (blades[c] or 0) / veg / 1000.0 if veg > 0 else None
        print(f"| {names.get(c, c)} | {fmt(veg)} | {fmt(veg / (ms[3] - ms[0]))} | {fmt(rate)} |")


if __name__ == "__main__":
    sys.exit(main())
