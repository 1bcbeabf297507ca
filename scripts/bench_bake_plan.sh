#!/bin/bash
# README Results, "Technique interface and bake jobs": a level's serial in-process bake vs the same
# jobs as a Ninja plan under -j2, alternating in one run, each into a fresh BOUNCE_CACHE (cooked
# assets shared and warm): wall and CPU (user + sys) seconds, and whether the entries are identical.
#   scripts/bench_bake_plan.sh [LEVEL] [ROUNDS]     (from the repository root, after a release build)
set -u
B=${BOUNCE:-$PWD/build/release/bounce}
L=$(realpath "${1:-content/levels/cornell-10.json}")
ROUNDS=${2:-3}
export BOUNCE_COOK_CACHE=${BOUNCE_COOK_CACHE:-$PWD/build/release/cache/cooked}
R=$(mktemp -d)
trap 'rm -rf "$R"' EXIT
for round in $(seq 1 "$ROUNDS"); do
  rm -rf "$R/serial" "$R/plan"; mkdir -p "$R/plan"
  /usr/bin/time -o "$R/s.time" -f "%e %U %S" env BOUNCE_CACHE="$R/serial" "$B" bake "$L" --force >/dev/null 2>&1
  /usr/bin/time -o "$R/p.time" -f "%e %U %S" sh -c "BOUNCE_CACHE='$R/plan' '$B' bake '$L' --plan '$R/plan/bake.ninja' >/dev/null 2>&1 && cd '$R/plan' && ninja -f bake.ninja -j2 >/dev/null 2>&1"
  same=$(diff -r "$R/serial" "$R/plan" -x bake.ninja -x .ninja_log -x .ninja_deps >/dev/null && echo identical || echo DIFFERENT)
  echo "$(cat "$R/s.time") $(cat "$R/p.time") $same" | awk -v r="$round" -v load="$(cut -d' ' -f1 /proc/loadavg)" \
    '{printf "round %d: serial %.1f s wall %.1f s cpu | plan+ninja -j2 %.1f s wall %.1f s cpu | wall ratio %.2f cpu ratio %.2f | entries %s | load %s\n", r, $1, $2+$3, $4, $5+$6, $4/$1, ($5+$6)/($2+$3), $7, load}'
done
