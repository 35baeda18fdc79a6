#!/usr/bin/env bash
# Wall time of POV-Ray 3.7 against our `render` on the same scenes, in one run:
#   benches/vs-povray.sh [SIZE]        (default 840: SIZE x SIZE pixels, no anti-aliasing)
# Scenes: torus, whitted-torus, barth, teapot, teapot-resultant (scenes/*.scene and their equivalents
# benches/pov/*.pov; the teapot's patches are converted from scenes/teapot.bpt here).
# Then the Standard Procedural Databases at 512 x 512 (NFF for us, the generators' .pov twins for
# POV-Ray; from $SPD_DIR, default ../shared/data/spd beside the repository, else scenes/spd; and
# jacks, lattice, rings, shells, sombrero, teapot and tree, which benches/spd/generate.py writes
# in both languages), with
# each renderer's peak memory (/usr/bin/time -v), and an n x n torus grid over a plane at 400 x 400
# (generated here in both languages; n = 3, 10, 30, 60). Times in seconds: wall and CPU (user +
# system), ratios ours / POV-Ray.
# Then issue 11's near-multiple-sheet surfaces of degree 16 and 20, near and far (see below).
# VS_POVRAY_ONLY=classic|spd|grid|sheets runs one section; SPD_SCENES="gears mount" some SPD scenes;
# VS_POVRAY_RUNS and VS_POVRAY_BEFORE (SPD and grid sections): see `compare` below.
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

only=${VS_POVRAY_ONLY:-all}
if [ "$only" = all ] || [ "$only" = classic ]; then
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
echo "size ${size}x${size}, $threads threads each"
fi

# One timed run of each renderer: wall time (s) and peak resident memory (MB), from GNU time.
# CPU time (user + system) is printed too: on a machine shared with other work, the wall time
# measures the machine's load as much as the renderer.
timed() { # LOG CMD... -> prints "WALL CPU MB"
    local log=$1; shift
    /usr/bin/time -v "$@" >"$log" 2>&1 || { echo "failed: $* (see $log)" >&2; exit 1; }
    awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); w = 0;
                    for (i = 1; i <= n; i++) w = w * 60 + p[i] }
                /User time|System time/ { c += $2 }
                /Maximum resident set size/ { m = $2 / 1024 }
                END { printf "%.3f %.3f %.1f\n", w, c, m }' "$log"
}

# VS_POVRAY_RUNS=N runs each comparison N times, interleaved (POV-Ray, [before,] ours, then
# again), and prints medians: of each time, and of the per-run ratios. VS_POVRAY_BEFORE=BINARY
# times a second `render` (an older build) in the same runs, printed as "before".
runs=${VS_POVRAY_RUNS:-1}
before=${VS_POVRAY_BEFORE:-}

median() { # NUMBERS... -> their median
    printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END {
        print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'
}

compare() { # NAME OURS-SCENE POV-SCENE SIZE
    local name=$1 ours=$2 pov=$3 px=$4 r
    local -a pw=() pc=() pm=() ow=() oc=() om=() bw=() bc=() bm=() rw=() rc=() brw=() brc=()
    for ((r = 0; r < runs; r++)); do
        read -r pw[r] pc[r] pm[r] < <(timed "$out/$name-povray.log" povray +I"$pov" \
            +L"$(dirname "$pov")" +O"$out/$name-povray.png" +W"$px" +H"$px" -A -D +WT"$threads")
        if [ -n "$before" ]; then
            read -r bw[r] bc[r] bm[r] < <(timed "$out/$name-before.log" "$before" "$ours" \
                -o "$out/$name-before.png" --size "${px}x${px}" --threads "$threads" --stats)
            brw[r]=$(awk -v a="${bw[r]}" -v b="${pw[r]}" 'BEGIN { print a / b }')
            brc[r]=$(awk -v a="${bc[r]}" -v b="${pc[r]}" 'BEGIN { print a / b }')
        fi
        read -r ow[r] oc[r] om[r] < <(timed "$out/$name-ours.log" "$render" "$ours" \
            -o "$out/$name-ours.png" --size "${px}x${px}" --threads "$threads" --stats)
        rw[r]=$(awk -v a="${ow[r]}" -v b="${pw[r]}" 'BEGIN { print a / b }')
        rc[r]=$(awk -v a="${oc[r]}" -v b="${pc[r]}" 'BEGIN { print a / b }')
    done
    if [ -n "$before" ]; then
        printf '%-17s %9.3f %9.3f %9.3f %7.2f %7.2f %9.3f %9.3f %9.3f %7.2f %7.2f %8.1f %8.1f %8.1f\n' \
            "$name" "$(median "${pw[@]}")" "$(median "${bw[@]}")" "$(median "${ow[@]}")" \
            "$(median "${brw[@]}")" "$(median "${rw[@]}")" \
            "$(median "${pc[@]}")" "$(median "${bc[@]}")" "$(median "${oc[@]}")" \
            "$(median "${brc[@]}")" "$(median "${rc[@]}")" \
            "$(median "${pm[@]}")" "$(median "${bm[@]}")" "$(median "${om[@]}")"
    else
        printf '%-17s %9.3f %9.3f %7.2f %9.3f %9.3f %7.2f %8.1f %8.1f\n' "$name" \
            "$(median "${pw[@]}")" "$(median "${ow[@]}")" "$(median "${rw[@]}")" \
            "$(median "${pc[@]}")" "$(median "${oc[@]}")" "$(median "${rc[@]}")" \
            "$(median "${pm[@]}")" "$(median "${om[@]}")"
    fi
}

header() { # TITLE
    if [ -n "$before" ]; then
        printf '%-17s %9s %9s %9s %7s %7s %9s %9s %9s %7s %7s %8s %8s %8s\n' "$1" "POV wall" \
            "bef wall" "our wall" "bef/POV" "our/POV" "POV CPU" "bef CPU" "our CPU" "bef/POV" \
            "our/POV" "POV MB" "bef MB" "our MB"
    else
        printf '%-17s %9s %9s %7s %9s %9s %7s %8s %8s\n' "$1" "POV wall" "our wall" ratio \
            "POV CPU" "our CPU" ratio "POV MB" "our MB"
    fi
}

if [ "$only" = all ] || [ "$only" = spd ]; then
spd=${SPD_DIR:-$root/../shared/data/spd}
[ -f "$spd/balls.nff" ] || spd=$root/../../shared/data/spd # from a worktree in wt/NAME
[ -f "$spd/balls.nff" ] || spd=$root/scenes/spd
echo
header "SPD (512x512)"
# The SPD scenes the shared data does not hold, written here by our generator in both languages.
for g in jacks lattice rings shells sombrero teapot tree; do
    python3 "$here/spd/generate.py" "$g" "$out/spd" >/dev/null
done
# jacks and sombrero at their default size are one jack (9 objects) and 1 922 triangles: also
# at size 4 (5 265 objects; 130 050 triangles).
for g in jacks sombrero; do python3 "$here/spd/generate.py" "$g" -s 4 "$out/spd" >/dev/null; done
for f in "$spd"/*.nff "$out/spd"/*.nff; do
    name=$(basename "$f" .nff)
    case " ${SPD_SCENES:-$name} " in *" $name "*) ;; *) continue ;; esac
    compare "$name" "$f" "${f%.nff}.pov" 512
done
fi

if [ "$only" = all ] || [ "$only" = grid ]; then
echo
header "torus grid (400)"
for n in 3 10 30 60; do
    # n x n tori (R = 0.35, r = 0.12, spacing 1) over a plane, seen from above and in front.
    awk -v n="$n" 'BEGIN {
        e = n * 0.9 + 3;
        printf "#world BackGnd = 0.2 Shadows = ON\n#camera Eye = (0, -%g, %g) LookAt = (0, 0, 0) Up = (0, 0, 1) ViewField = 50\n", e, e * 0.8;
        printf "#light Source = (%g, -%g, %g) Color = 1\n", e, e, 2 * e;
        printf "#object Type = PLANE Origin = (0, 0, -0.2) Normal = (0, 0, 1) Cs = (0.6, 0.6, 0.6)\n";
        for (i = 0; i < n; i++) for (j = 0; j < n; j++)
            printf "#object Type = TORUS Center = (%g, %g, 0) Axis = (0, 0, 1) MajorRadius = 0.35 MinorRadius = 0.12 Cs = (0.8, 0.3, 0.2) Ka = 0.1 Kd = 0.7\n", i - (n - 1) / 2, j - (n - 1) / 2 }' \
        >"$out/grid-$n.scene"
    awk -v n="$n" 'BEGIN {
        e = n * 0.9 + 3;
        printf "#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n";
        printf "camera { location <0, -%g, %g> sky <0, 0, 1> up <0, 0, 1> right <-1, 0, 0> angle 50 look_at <0, 0, 0> }\n", e, e * 0.8;
        printf "background { rgb 0.2 }\nlight_source { <%g, -%g, %g> rgb 1 }\n", e, e, 2 * e;
        printf "plane { z, -0.2 pigment { rgb 0.6 } finish { ambient 0.1 diffuse 0.9 } }\n";
        for (i = 0; i < n; i++) for (j = 0; j < n; j++)
            printf "torus { 0.35, 0.12 rotate x*90 translate <%g, %g, 0> pigment { rgb <0.8, 0.3, 0.2> } finish { ambient 0.1 diffuse 0.7 } }\n", i - (n - 1) / 2, j - (n - 1) / 2 }' \
        >"$out/grid-$n.pov"
    compare "grid-$((n * n))" "$out/grid-$n.scene" "$out/grid-$n.pov" 400
done
fi
if [ "$only" = all ] || [ "$only" = sheets ]; then
# Issue 11: degree-16 and degree-20 powers of the torus quartic minus a constant (sheets that
# nearly touch; scenes/torus-sheets*.scene, benches/pov/torus-sheets*.pov), from the scene's
# eye and from 1000 times farther (the view angle narrowed by 1000). VS_POVRAY_SHEETS_SIZE
# (default 300): POV-Ray's Sturm solver takes minutes at 840 x 840 on the degree-20 scene.
sheets=${VS_POVRAY_SHEETS_SIZE:-300}
echo
header "sheets ($sheets)"
for deg in 16 20; do
    compare "sheets$deg" "$root/scenes/torus-sheets$deg.scene" "$here/pov/torus-sheets$deg.pov" "$sheets"
    sed 's/Eye = (0, -8, 5)/Eye = (0, -8000, 5000)/; s/ViewField = 50/ViewField = 0.05/' \
        "$root/scenes/torus-sheets$deg.scene" >"$out/far-sheets$deg.scene"
    sed 's/location <0, -8, 5>/location <0, -8000, 5000>/; s/angle 50/angle 0.05/' \
        "$here/pov/torus-sheets$deg.pov" >"$out/far-sheets$deg.pov"
    compare "far-sheets$deg" "$out/far-sheets$deg.scene" "$out/far-sheets$deg.pov" "$sheets"
done
fi
echo "$threads threads each, $runs run(s) each (medians); images and logs in $out"
