#!/usr/bin/env bash
# Before/after timing of two `render` binaries on the classic scenes, interleaved:
# for each round, each scene, BEFORE then AFTER (840² as the scenes are written, the
# binaries' default threads, whole process). Prints the median user CPU and wall time of
# each and the after/before ratios. Used for issue 10's "within noise of before"
# (docs/speed.md, "Redesign before/after").
#
#   benches/ab-render.sh BEFORE_BIN AFTER_BIN [ROUNDS] [SCENE...]
set -euo pipefail
before=${1:?usage: ab-render.sh BEFORE_BIN AFTER_BIN [ROUNDS] [SCENE...]}
after=${2:?usage: ab-render.sh BEFORE_BIN AFTER_BIN [ROUNDS] [SCENE...]}
rounds=${3:-5}
shift $(( $# < 3 ? $# : 3 ))
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(torus whitted-torus barth teapot)
here=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for _ in $(seq "$rounds"); do
  for s in "${scenes[@]}"; do
    for which in before after; do
      bin=$before; [ "$which" = after ] && bin=$after
      /usr/bin/time -f "$s $which %U %e" -a -o "$out/times" \
        "$bin" "$here/scenes/$s.scene" -o "$out/$which-$s.png" > /dev/null
    done
  done
done
python3 - "$out/times" <<'PY'
import collections, statistics, sys
d = collections.defaultdict(list)
for line in open(sys.argv[1]):
    s, which, user, wall = line.split()
    d[(s, which)].append((float(user), float(wall)))
print("| scene | before CPU (range) | after CPU (range) | CPU ratio | wall ratio |")
print("|---|---|---|---|---|")
for s in dict.fromkeys(k[0] for k in d):
    b, a = d[(s, "before")], d[(s, "after")]
    mb, ma = statistics.median(x[0] for x in b), statistics.median(x[0] for x in a)
    wb, wa = statistics.median(x[1] for x in b), statistics.median(x[1] for x in a)
    rng = lambda v: f"{min(x[0] for x in v):.2f}–{max(x[0] for x in v):.2f}"
    print(f"| {s} | {mb:.2f} s ({rng(b)}) | {ma:.2f} s ({rng(a)}) | {ma/mb:.3f} | {wa/wb:.3f} |")
PY
