#!/usr/bin/env bash
# Wall time of POV-Ray 3.7 against our `render` on the same scenes, in one run:
#   benches/vs-povray.sh [SIZE]        (default 840: SIZE x SIZE pixels, no anti-aliasing)
# Scenes: torus, whitted-torus, barth, teapot, teapot-resultant (scenes/*.scene and their equivalents
# benches/pov/*.pov; the teapot's patches are converted from scenes/teapot.bpt here).
# Both renderers get every core (`nproc`). Prints each wall time and the ratio ours / POV-Ray,
# then the tracing phase alone: POV-Ray's "Trace Time" and ours (`--stats`, "trace").
# Without POV-Ray it says so and exits 0. Images go to a temporary directory, printed at the end.
set -euo pipefail

size=${1:-840}
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")

if ! command -v povray >/dev/null 2>&1; then
    echo "POV-Ray is missing (apt-get install povray): nothing to compare."
    exit 0
fi

threads=$(nproc)
target=${CARGO_TARGET_DIR:-$root/target}
(cd "$root" && cargo build --release -q -p render-cli --bin render)
render="$target/release/render"
out=$(mktemp -d)

now() { date +%s.%N; }

# scenes/teapot.bpt -> one POV-Ray bicubic_patch per 3x3 patch (rows of 4 points, as stored).
awk 'NR == 1 { next }
     NF == 2 { if (n) print "}"; n = 0; printf "bicubic_patch { type 1 flatness 0.01 u_steps 3 v_steps 3\n"; next }
     NF == 3 { printf "%s  <%s, %s, %s>\n", (n ? "," : ""), $1, $2, $3; n++ }
     END { if (n) print "}" }' "$root/scenes/teapot.bpt" >"$out/teapot-patches.inc"

printf '%-17s %12s %12s %14s %14s %14s\n' scene "POV-Ray (s)" "ours (s)" "ours/POV-Ray" \
    "POV trace (s)" "our trace (s)"
# teapot-resultant is teapot.scene with Kajiya's resultant: the same POV-Ray file.
for scene in torus whitted-torus barth teapot teapot-resultant; do
    pov=${scene%-resultant}
    t0=$(now)
    povray +I"$here/pov/$pov.pov" +L"$out" +O"$out/$scene-povray.png" +W"$size" +H"$size" \
        -A -D +WT"$threads" >"$out/$scene-povray.log" 2>&1 ||
        { echo "povray failed on $scene: see $out/$scene-povray.log" >&2; exit 1; }
    t1=$(now)
    "$render" "$root/scenes/$scene.scene" -o "$out/$scene-ours.png" --size "${size}x${size}" \
        --threads "$threads" --stats >"$out/$scene-ours.log" 2>&1 ||
        { echo "render failed on $scene: see $out/$scene-ours.log" >&2; exit 1; }
    t2=$(now)
    pov_trace=$(sed -n 's/.*Trace Time:.*(\([0-9.]*\) seconds).*/\1/p' "$out/$scene-povray.log")
    our_trace=$(awk '$1 == "parse" { for (i = 1; i < NF; i++) if ($i == "trace") print $(i + 1) / 1000 }' \
        "$out/$scene-ours.log")
    awk -v s="$scene" -v a="$t0" -v b="$t1" -v c="$t2" -v pt="${pov_trace:-nan}" -v ot="${our_trace:-nan}" \
        'BEGIN { p = b - a; o = c - b;
                 printf "%-17s %12.3f %12.3f %14.2f %14s %14s\n", s, p, o, o / p, pt, ot }'
done
echo "size ${size}x${size}, $threads threads each; images and logs in $out"
