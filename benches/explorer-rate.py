#!/usr/bin/env python3
"""Measures the explorer's preview latency and drag rate (issue 14's targets).

Starts `render serve --port 0` (the release binary by default), then for each scene:

- edit: sends `POST /api/render` with `scale: 8` (the page's 1/8 preview) N times, the scene
  text changed each time by a trailing comment (a real edit: parse, build, prepare, trace,
  encode, base64, JSON), and times each round trip on loopback;
- drag: sends N previews in a row with the eye rotated 3 degrees about the look-at point's
  vertical axis each time (what a mouse drag does: the page sends the next preview when the
  previous one has arrived), and reports previews per second over the whole run;
- full: one full-size render (`scale: 1`) through the same API, against the CLI's wall time for
  `render SCENE -o /tmp/…png` of the same binary.

Prints a markdown table. Usage:

    cargo build --release -p render-cli
    python3 benches/explorer-rate.py [--bin target/release/render] [--n 20] [scenes...]

Scene names are files of `scenes/` (default: barth torus). The machine's load matters: run it on
a quiet machine and say in docs/explorer.md whether it was.
"""
import argparse
import json
import math
import os
import re
import statistics
import subprocess
import sys
import time
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EYE_RE = re.compile(r"Eye\s*=\s*\(([^)]*)\)")


def post(url, body):
    data = json.dumps(body).encode()
    req = urllib.request.Request(url, data=data, headers={"Content-Type": "application/json"})
    t0 = time.perf_counter()
    with urllib.request.urlopen(req, timeout=600) as resp:
        payload = json.loads(resp.read())
    return time.perf_counter() - t0, payload


def rotated(text, degrees):
    """The scene text with `Eye` turned by `degrees` about the z axis through the origin
    (the look-at point of the measured scenes)."""
    m = EYE_RE.search(text)
    x, y, z = (float(v) for v in m.group(1).split(","))
    a = math.radians(degrees)
    x, y = x * math.cos(a) - y * math.sin(a), x * math.sin(a) + y * math.cos(a)
    return text[: m.start()] + f"Eye = ({x:.6f}, {y:.6f}, {z:.6f})" + text[m.end() :]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", default=os.path.join(ROOT, "target", "release", "render"))
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("scenes", nargs="*", default=["barth", "torus"])
    args = ap.parse_args()

    server = subprocess.Popen(
        [args.bin, "serve", "--port", "0", "--scenes", os.path.join(ROOT, "scenes")],
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
        text=True,
    )
    try:
        line = server.stdout.readline()
        base = re.search(r"(http://\S+/)", line).group(1)
        rows = []
        for name in args.scenes:
            path = os.path.join(ROOT, "scenes", name + ".scene")
            text = open(path).read()
            api = base + "api/render"
            # Warm-up: the first request starts the pool.
            post(api, {"session": "bench", "scene": text, "scale": 8})
            edits = []
            for i in range(args.n):
                dt, _ = post(api, {"session": "bench", "scene": text + f"\n// edit {i}\n", "scale": 8})
                edits.append(dt)
            t0 = time.perf_counter()
            for i in range(args.n):
                post(api, {"session": "bench", "scene": rotated(text, 3.0 * (i + 1)), "scale": 8})
            drag_rate = args.n / (time.perf_counter() - t0)
            full_dt, full = post(api, {"session": "bench", "scene": text, "scale": 1})
            t0 = time.perf_counter()
            subprocess.run(
                [args.bin, path, "-o", f"/tmp/explorer-rate-{name}.png"],
                check=True,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            cli_dt = time.perf_counter() - t0
            rows.append(
                (
                    name,
                    statistics.median(edits) * 1e3,
                    min(edits) * 1e3,
                    max(edits) * 1e3,
                    drag_rate,
                    full["width"],
                    full_dt,
                    cli_dt,
                )
            )
        print("| scene | edit → preview, median (min–max) | drag previews/s | full size | full via API | CLI wall |")
        print("| --- | --- | --- | --- | --- | --- |")
        for name, med, lo, hi, rate, w, full_dt, cli_dt in rows:
            print(
                f"| {name}.scene | {med:.0f} ms ({lo:.0f}–{hi:.0f}) | {rate:.1f} | {w}² |"
                f" {full_dt:.2f} s | {cli_dt:.2f} s |"
            )
    finally:
        server.terminate()
        server.wait()


if __name__ == "__main__":
    sys.exit(main())
