#!/usr/bin/env python3
"""scripts/soak's short form (issue 42 item 7; the 30-minute run is a script, not a test): one
minute of the looping realtime flight over nginx through scripts/fault-proxy, with the Vulkan
validation layer on. It must exit 0 with every request accounted for, the faults must really
have happened, the rows and the plot must be there; its usage mistakes exit 2. Then the verdict
itself (scripts/soak_report.py) on made-up samples: a leak of 20 % over 30 minutes fails, a
flat run passes, and runs shorter than 10 minutes report flatness without judging it.

  soak_test.py REPO BUILD TMP
"""
import csv
import json
import os
import shutil
import subprocess
import sys

repo, build, tmp = sys.argv[1:4]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAILED:", what)


shutil.rmtree(tmp, ignore_errors=True)
os.makedirs(tmp)
soak = os.path.join(repo, "scripts", "soak")

# Usage mistakes: exit 2, one line, nothing run.
r = subprocess.run([soak, "--minutes"], capture_output=True, text=True)
check(r.returncode == 2, f"--minutes without a value exits 2 (got {r.returncode})")
os.makedirs(os.path.join(tmp, "taken"))
r = subprocess.run([soak, "--out", os.path.join(tmp, "taken"), "--build", build], capture_output=True, text=True)
check(r.returncode == 2 and "already exists" in r.stderr, f"an existing --out exits 2 ({r.returncode}: {r.stderr})")

# The dataset: the Zion sample as the README imports it.
z = os.path.join(repo, "..", "shared", "datasets", "zion")
dataset = os.path.join(tmp, "zion")
r = subprocess.run([os.path.join(build, "app", "vegstream"), "import", "--dem", f"{z}/srtm.tif", "--imagery-bands",
                    f"{z}/landsat_b4.tif,{z}/landsat_b3.tif,{z}/landsat_b2.tif", "--radiometry", "reflectance",
                    "--out", dataset], capture_output=True, text=True)
check(r.returncode == 0, f"import: {r.stderr[-300:]}")

out = os.path.join(tmp, "run")
r = subprocess.run([soak, "--minutes", "1", "--every-s", "5", "--validate", "--http-cache", "--out", out, "--dataset", dataset,
                    "--build", build], capture_output=True, text=True, timeout=600)
print(r.stdout)
print(r.stderr, file=sys.stderr)
check(r.returncode == 0, f"a one-minute soak exits 0 (got {r.returncode})")
report = json.load(open(os.path.join(out, "report.json")))
check(report["ok"] and report["soak_flight_exit"] == 0, "the report says ok")
check(all(v[2] for v in report["accounting"].values()), "every request accounted for")
check(not report["flat_judged"], "one minute is too short to judge flatness")
proxy = report["proxy"]
check(proxy["resets"] > 0 and proxy["status503"] + proxy["status500"] > 0, f"the faults happened: {proxy}")
check(proxy["upstream_status"].get("200", 0) > 20, "tiles came through the proxy")
rows = list(csv.DictReader(open(os.path.join(out, "samples.csv"))))
check(len(rows) >= 12, f"a row every 5 s for a minute ({len(rows)})")
check(int(rows[-1]["frames"]) >= 30, f"frames were drawn ({rows[-1]['frames']}: at least one every 2 s, even on a loaded 2-core machine)")
check(all(int(r["fds"]) > 0 and int(r["rss_bytes"]) > 0 and int(r["gpu_bytes"]) > 0 for r in rows), "figures measured")
check(int(rows[-1]["cache_bytes"]) > 0, "the HTTP cache took tiles")
check(open(os.path.join(out, "soak.png"), "rb").read(8) == b"\x89PNG\r\n\x1a\n", "the plot is a PNG")
check("validation" not in open(os.path.join(out, "soak_flight.log")).read(), "validation silent")

# The verdict on made-up samples.
header = open(os.path.join(out, "samples.csv")).readline().strip().split(",")


def verdict(name, minutes, rss_at):
    d = os.path.join(tmp, name)
    os.makedirs(d)
    shutil.copy(os.path.join(out, "proxy.json"), d)
    last = {k: float(v) for k, v in rows[-1].items()}
    with open(os.path.join(d, "samples.csv"), "w") as f:
        w = csv.writer(f)
        w.writerow(header)
        for i in range(int(minutes * 6) + 1):
            row = dict(last, wall_s=i * 10.0, rss_bytes=rss_at(i * 10.0 / 60.0, minutes), fds=16.0)
            w.writerow([row[k] for k in header])
    return subprocess.run([sys.executable, os.path.join(repo, "scripts", "soak_report.py"), d, str(minutes), "0"],
                          capture_output=True, text=True).returncode


flat = lambda m, total: 500e6 + (50e6 if m < 2 else 0)       # warm-up, then flat
leak = lambda m, total: 500e6 * (1 + 0.20 * m / total)       # 20 % over the run: 9 % between the windows
check(verdict("flat30", 30, flat) == 0, "a flat 30-minute run passes")
check(verdict("leak30", 30, leak) == 1, "a 30-minute run leaking 20 % fails")
check(verdict("leak5", 5, leak) == 0, "a 5-minute run is not judged on flatness")
if failures:
    sys.exit(f"{len(failures)} checks failed")
print("soak short form: all checks passed")
