#!/usr/bin/env python3
"""The verdict of scripts/soak: reads DIR/samples.csv (bench/soak_flight) and DIR/proxy.json
(scripts/fault-proxy), writes DIR/report.json, DIR/report.md and DIR/soak.png, prints the
report, and exits 0 only when soak_flight's STATUS was 0 and every check held (scripts/soak's
header says which).

  soak_report.py DIR MINUTES STATUS
"""
import csv
import json
import os
import sys

FLAT_FROM_MINUTES = 10.0  # shorter runs report flatness without judging it (still warming up)


def read_samples(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def window_means(rows, key, minutes):
    """Mean of `key` over the first and the last 40 % of the run after a warm-up of a sixth."""
    end = max(r["wall_s"] for r in rows)
    warm = end / 6.0
    span = (end - warm) * 0.4
    first = [r[key] for r in rows if warm <= r["wall_s"] <= warm + span]
    last = [r[key] for r in rows if r["wall_s"] >= end - span]
    if not first or not last:
        return None
    return sum(first) / len(first), sum(last) / len(last), warm, span


def flatness(rows, minutes):
    out = {}
    for key, slack in (("rss_bytes", 0.05), ("heap_bytes", 0.05), ("gpu_bytes", 0.05), ("fds", None)):
        if key not in rows[0]:
            continue
        w = window_means(rows, key, minutes)
        if w is None:
            out[key] = {"ok": False, "why": "too few samples"}
            continue
        first, last, warm, span = w
        ok = (last <= first * (1 + slack) and last >= first * (1 - slack)) if slack else abs(last - first) <= 8
        out[key] = {"first": first, "last": last, "ratio": last / first if first else None, "ok": ok,
                    "warmup_s": warm, "window_s": span}
    return out


def accounting(last, proxy):
    started = last["requests_started"]
    ended = (last["requests_completed"] + last["requests_missing"] + last["requests_failed"] +
             last["requests_cancelled"] + last["requests_in_flight"])
    received = proxy["received"]
    disposed = (proxy["forwarded"] + proxy["status503"] + proxy["status500"] + proxy["resets"] + proxy["aborted"] +
                proxy["failed"])
    ok200 = proxy["upstream_status"].get("200", 0)
    network = last["requests_completed"] - last["cache_hits"]
    return {
        "source: started = completed + missing + failed + cancelled + in flight": [started, ended, started == ended],
        "proxy: received = forwarded + 503 + 500 + resets + aborted + failed": [received, disposed, received == disposed],
        "completed over the network <= proxy's 200s": [network, ok200, network <= ok200],
        # libcurl sends a request again by itself, on a new connection, when the reused one it
        # went out on is reset before any answer: a reset can bring one attempt the source never saw.
        "proxy's requests <= source's attempts (started + retries) + the proxy's resets":
            [received, started + last["retries"] + proxy["resets"],
             received <= started + last["retries"] + proxy["resets"]],
    }


def plot(rows, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = [r["wall_s"] / 60.0 for r in rows]
    fig, axes = plt.subplots(4, 1, figsize=(9, 10), sharex=True)
    mib = 1.0 / (1 << 20)
    axes[0].plot(t, [r["rss_bytes"] * mib for r in rows], label="resident (VmRSS)")
    if "heap_bytes" in rows[0]:
        axes[0].plot(t, [r["heap_bytes"] * mib for r in rows], label="heap in use (mallinfo2)")
    axes[0].plot(t, [r["bytes_resident_cpu"] * mib for r in rows], label="decoded tiles")
    axes[0].set_ylabel("MiB")
    axes[1].plot(t, [r["gpu_bytes"] * mib for r in rows], label="GPU allocations")
    axes[1].plot(t, [r["cache_bytes"] * mib for r in rows], label="HTTP cache on disk")
    axes[1].set_ylabel("MiB")
    axes[2].plot(t, [r["fds"] for r in rows], label="open files")
    axes[2].set_ylabel("count")
    for key in ("requests_started", "requests_completed", "requests_failed", "retries"):
        axes[3].plot(t, [r[key] for r in rows], label=key.replace("requests_", ""))
    axes[3].set_ylabel("requests")
    axes[3].set_xlabel("minutes")
    for a in axes:
        a.legend(loc="upper left", fontsize=8)
        a.grid(alpha=0.3)
    axes[0].set_title(title)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main():
    out, minutes, status = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
    rows = read_samples(os.path.join(out, "samples.csv"))
    proxy = json.load(open(os.path.join(out, "proxy.json")))
    last = rows[-1]
    flat = flatness(rows, minutes)
    judged = minutes >= FLAT_FROM_MINUTES
    acc = accounting(last, proxy)
    ok = status == 0 and all(v[2] for v in acc.values()) and (not judged or all(v["ok"] for v in flat.values()))
    report = {"minutes": minutes, "soak_flight_exit": status, "frames": last["frames"], "flat": flat,
              "flat_judged": judged, "accounting": acc, "proxy": proxy, "ok": ok}
    with open(os.path.join(out, "report.json"), "w") as f:
        json.dump(report, f, indent=1)
    lines = [f"# soak: {minutes:g} min, {int(last['frames'])} frames, soak_flight exit {status}: "
             f"{'PASS' if ok else 'FAIL'}", "",
             f"Flat memory ({'judged' if judged else f'reported only: judged from {FLAT_FROM_MINUTES:g} min'}):", ""]
    for key, v in flat.items():
        if "first" in v:
            lines.append(f"- {key}: first window {v['first']:.0f}, last {v['last']:.0f} "
                         f"(x{v['ratio']:.3f}), {'ok' if v['ok'] else 'NOT FLAT'}")
        else:
            lines.append(f"- {key}: {v['why']}")
    lines += ["", "Every request accounted for:", ""]
    for name, (a, b, good) in acc.items():
        lines.append(f"- {name}: {a:.0f} vs {b:.0f}: {'ok' if good else 'NO'}")
    lines += ["", f"Proxy: {json.dumps(proxy, sort_keys=True)}"]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "report.md"), "w") as f:
        f.write(text)
    print(text, end="")
    plot(rows, os.path.join(out, "soak.png"), f"vegstream soak: {minutes:g} min over a fault proxy")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
