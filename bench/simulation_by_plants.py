# gpu_simulation_ms binned by the plants drawn, per recording (issue 19: the field's cost must not
# grow with plants): python3 bench/simulation_by_plants.py DIR NAME… reads DIR/NAME/frames.csv.
import csv, sys, statistics
for name in sys.argv[2:]:
    rows = list(csv.DictReader(open(f"{sys.argv[1]}/{name}/frames.csv")))
    pairs = [(float(r["plants"] or 0), float(r["gpu_simulation_ms"])) for r in rows if r.get("gpu_simulation_ms")]
    bins = [(0, 1), (1, 50000), (50000, 200000), (200000, 400000), (400000, 1e12)]
    print(f"\n{name}: gpu_simulation_ms by plants drawn (frames, median, p99)")
    for lo, hi in bins:
        v = sorted(ms for p, ms in pairs if lo <= p < hi)
        if v:
            print(f"  plants {lo:>8.0f} … {hi:<8.0f} frames {len(v):5d}  median {statistics.median(v):.4f}  p99 {v[int(0.99*(len(v)-1))]:.4f}")
    cpu = sorted(float(r["cpu_simulation_ms"]) for r in rows if r.get("cpu_simulation_ms"))
    print(f"  cpu_simulation_ms median {statistics.median(cpu):.4f} p99 {cpu[int(0.99*(len(cpu)-1))]:.4f}")
