#!/usr/bin/env python3
"""bench/gpu_measure_compare.py and bench/gpu-measure's --compare, --set 4k and --only NAME:FPS on
small synthetic recordings (summary.json + frames.csv as flight/summary.cpp and
flight/frame_columns.cpp write them), made in a temporary directory; no GPU, no build."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
COMPARE = os.path.join(ROOT, "bench", "gpu_measure_compare.py")
MEASURE = os.path.join(ROOT, "bench", "gpu-measure")
PASSES = ["Terrain", "Plants"]


def percentile(v, q):  # flight/summary.cpp's percentile: linear between the two nearest ranks
    v = sorted(v)
    pos = q / 100.0 * (len(v) - 1)
    lo = int(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def write_recording(d, path="benchmark-30s", fps=60, gpu=2.0, plants_ms=1.0, plants=1000, trees=None):
    """A 30 s recording at 1 frame per second: every 10th frame's times are 1.5 × the others'."""
    cols = ["frame", "t_s", "cpu_frame_ms", "gpu_frame_ms", "gpu_terrain_ms", "gpu_plants_ms", "wall_ms",
            "recorder_ms", "terrain_triangles", "plants", "plant_triangles", "trees_full", "trees_reduced",
            "trees_impostor"]
    rows = []
    for i in range(31):
        k = 1.5 if i % 10 == 9 else 1.0
        tree = ["", "", ""] if trees is None else [trees, 10, 5]
        rows.append([i, float(i), 1.0 * k, gpu * k, 0.5 * k, plants_ms * k, 3.0 * k, 0.001, 50000, plants,
                     plants * 20] + tree)
    os.makedirs(d)
    with open(os.path.join(d, "frames.csv"), "w", newline="") as f:
        csv.writer(f).writerows([cols] + rows)
    times = {}
    for c in cols:
        if c.endswith("_ms"):
            v = [r[cols.index(c)] for r in rows]
            times[c] = {q: percentile(v, float(q[1:])) for q in ("p50", "p95", "p99")} | {"max": max(v)}
    rec = {"device": {"name": "Synthetic GPU", "driver": "1.0"}, "size": [1920, 1080], "msaa": 4, "fps": fps,
           "frames_in_flight": 3, "path": {"name": path}, "per_pass_gpu_times_meaningful": True,
           "gpu_passes": PASSES}
    with open(os.path.join(d, "summary.json"), "w") as f:
        json.dump({"summary_version": 1, "recording": rec, "frames": len(rows), "times_ms": times}, f)


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True)


def table_row(out, figure):
    """The cells after the figure of the first table row naming figure."""
    for line in out.splitlines():
        if line.startswith(f"| {figure} |"):
            return [c.strip() for c in line.strip("|").split("|")][1:]
    raise AssertionError(f"no row {figure!r} in:\n{out}")


class CompareTwoDirectories(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        t = self.tmp.name
        self.base, self.new = os.path.join(t, "base"), os.path.join(t, "new")
        write_recording(os.path.join(self.base, "default"))
        write_recording(os.path.join(self.base, "kolob-forest"), path="kolob-forest", trees=300)
        write_recording(os.path.join(self.base, "canyon"), path="canyon-run")
        # The plants pass twice as slow, 10 % fewer plants; the GPU frame 5 % slower (not flagged).
        write_recording(os.path.join(self.new, "default"), gpu=2.1, plants_ms=2.0, plants=900)
        write_recording(os.path.join(self.new, "kolob-forest"), path="kolob-forest", trees=250)
        write_recording(os.path.join(self.new, "dense"), path="benchmark-30s")

    def tearDown(self):
        self.tmp.cleanup()

    def test_ratios_and_flags(self):
        r = run(sys.executable, COMPARE, self.base, self.new)
        self.assertEqual(r.returncode, 0, r.stderr)
        default = r.stdout.split("### default")[1].split("###")[0]
        self.assertEqual(table_row(default, "gpu_plants_ms p99")[2], "**2.00 ▲ REGRESSION**")
        self.assertEqual(table_row(default, "gpu_plants_ms p50"), ["2.000", "1.000", "**2.00 ▲ REGRESSION**"])
        self.assertEqual(table_row(default, "gpu_frame_ms p99")[2], "1.05")
        self.assertEqual(table_row(default, "gpu_terrain_ms p50")[2], "1.00")
        self.assertEqual(table_row(default, "wall_ms p99")[2], "1.00")
        self.assertEqual(table_row(default, "plants (t 10–20 s, median)"), ["900", "1000", "**0.90 ▼ DROPPED**"])
        self.assertNotIn("trees drawn", default)  # neither side has trees
        kolob = r.stdout.split("### kolob-forest")[1]
        self.assertEqual(table_row(kolob, "trees drawn (median)"), ["265", "315", "**0.84 ▼ DROPPED**"])
        self.assertIn("Not compared: new only dense; base only canyon.", r.stdout)
        self.assertIn("**Flagged: 4**", r.stdout)

    def test_settings_that_differ_are_named(self):
        write_recording(os.path.join(self.base, "dense"), fps=10)
        r = run(sys.executable, COMPARE, self.base, self.new)
        self.assertIn("Not measured alike: fps 60 (base 10).", r.stdout.split("### dense")[1])

    def test_a_missing_or_empty_base_is_one_line_and_exit_2(self):
        missing = os.path.join(self.tmp.name, "nowhere")
        for base in (missing, os.path.join(self.new, "default")):  # the second holds no NAME/summary.json
            r = run(sys.executable, COMPARE, base, self.new)
            self.assertEqual(r.returncode, 2)
            self.assertEqual(r.stdout, "")
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn(base, r.stderr)


FAKE_RUNNER = """#!/usr/bin/env python3
# gpu-measure's --runner for the test: `vegstream record DATASET --path P --out DIR … --fps F` writes a
# synthetic recording (GPU frame 3 ms) and prints its arguments; bench_* are not run.
import sys
sys.path.insert(0, %r)
from gpu_measure_compare_test import write_recording
a = sys.argv[1:]
print(" ".join(a))
if a[:2] == ["vegstream", "record"]:
    path = a[a.index("--path") + 1].rsplit("/", 1)[-1].removesuffix(".json")
    write_recording(a[a.index("--out") + 1], path=path, fps=int(a[a.index("--fps") + 1]), gpu=3.0)
"""


class GpuMeasureOptions(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        t = self.tmp.name
        self.dataset = os.path.join(t, "dataset")
        os.makedirs(self.dataset)
        with open(os.path.join(self.dataset, "dataset.json"), "w") as f:
            f.write("{}")
        self.runner = os.path.join(t, "fake-runner")
        with open(self.runner, "w") as f:
            f.write(FAKE_RUNNER % os.path.dirname(os.path.abspath(__file__)))
        os.chmod(self.runner, 0o755)

    def tearDown(self):
        self.tmp.cleanup()

    def measure(self, *args):
        return run("bash", MEASURE, "--dataset", self.dataset, "--runner", self.runner, "--no-bench", *args)

    def test_the_4k_set_with_compare(self):
        base = os.path.join(self.tmp.name, "base")
        write_recording(os.path.join(base, "default"))
        write_recording(os.path.join(base, "canyon"), path="canyon-run", fps=10)
        out = os.path.join(self.tmp.name, "m")
        r = self.measure("--set", "4k", "--out", out, "--compare", base)
        self.assertEqual(r.returncode, 0, r.stderr)
        records = [line for line in r.stdout.splitlines() if line.startswith("vegstream record")]
        self.assertEqual(len(records), 5, r.stdout)
        for line in records:
            self.assertIn("--size 3840x2160 --msaa 4", line)
            self.assertIn("--fps 10" if "canyon-run" in line else "--fps 60", line)
        names = sorted(n for n in os.listdir(out) if os.path.isfile(os.path.join(out, n, "summary.json")))
        self.assertEqual(names, ["canyon", "default", "dense", "kolob-forest", "meadow-wind"])
        with open(os.path.join(out, "report.md")) as f:
            report = f.read()
        self.assertIn("| canyon | canyon-run (10 fps) |", report)
        self.assertIn(f"## Against {base}", report)
        self.assertEqual(table_row(report.split("### default")[1], "gpu_frame_ms p50")[2], "**1.50 ▲ REGRESSION**")
        self.assertIn(f"## Against {base}", r.stdout)  # the report, comparison included, on stdout

    def test_a_missing_compare_base_stops_before_measuring(self):
        out = os.path.join(self.tmp.name, "m")
        r = self.measure("--out", out, "--compare", os.path.join(self.tmp.name, "nowhere"))
        self.assertEqual(r.returncode, 2)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertIn("nowhere", r.stderr)
        self.assertFalse(os.path.exists(out))

    def test_only_with_a_bad_fps_is_a_usage_mistake(self):
        r = self.measure("--out", os.path.join(self.tmp.name, "m"), "--only", "canyon:fast")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--only canyon:fast", r.stderr)


if __name__ == "__main__":
    unittest.main()
