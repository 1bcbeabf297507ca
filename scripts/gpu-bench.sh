#!/usr/bin/env bash
# Every GPU table of the README from one call of the accelerator tool (README "Benchmarks on a GPU").
#
#   scripts/gpu-bench.sh pack [--build DIR] [--no-warm]
#       Here, after a release build. Writes .gpu-pack/bounce.tar.xz: `cmake --install` of the build
#       (bin/bounce, share/bounce/{shaders,content,tools}), lib/ with every shared library `ldd`
#       lists that a bare machine lacks (Embree, TBB, Draco, OpenSubdiv, GLFW, meshoptimizer, stb,
#       the Vulkan loader, ...), sys/ with this machine's C and C++ runtime and dynamic linker (used
#       only where the target's are too old to run bounce), and cache/ with every level's cooked
#       assets, probe volume and DNRT fields (--no-warm: none; the benchmarks then bake there).
#       Also fetches the Vulkan loader and GL dispatch packages into .gl/ as the device tool's
#       README describes (the NVIDIA driver's Vulkan ICD needs libGLdispatch).
#   scripts/gpu-bench.sh run [--quick] [--only LIST] [--budget SECONDS] [--out DIR] [--device NAME] [--bundled-libc]
#       There (or here). Unpacks the pack into a fresh temporary folder and runs, each step under what
#       is left of one time budget (default 300 s), writing into $OUT (else --out, else ./gpu-bench-out):
#         log.txt                  every command and its output, the machine and device, per-step seconds
#         dnrt-1366x768.csv        bounce bench dnrt at the DNRT paper's resolution
#         dnrt-1280x720.csv        bounce bench dnrt at the README's resolution
#         vlm-lights.csv           bounce bench vlm-lights (thesis Table 5.1), 1280x720
#         vlm-k.csv                bounce bench vlm-k (thesis Table 5.3), 1280x720
#         rtf-profile.csv          bounce profile of cornell-5 with dnrt and rtf in the same run, 1280x720:
#                                  RTF's shading per object against DNRT's (issue 14's cost goal)
#         rtf-scenes.csv           bounce bench rtf on cornell-5's field settings, 1280x720, RTF shaded
#                                  at full, half and quarter resolution (column `shading`); rtf-objects.csv
#                                  its per-object bake and CPCA lines
#         profile.csv              bounce profile of every content level, 1280x720 (level column first)
#         vlm-grid.csv             bounce bench vlm-grid (thesis Table 5.2) on every core
#       Steps: dnrt1366 dnrt720 rtf vlm-lights vlm-k profile vlm-grid, in that order (most wanted first);
#       --only keeps some of them, for a rerun. --quick: tiny resolutions, 1-2 frames, fewer
#       settings (a rehearsal, minutes on lavapipe). --device: Vulkan device substring (default
#       NVIDIA, none with --quick). --bundled-libc: start bounce through the packed dynamic linker
#       even where the target's C++ runtime would do. Exit 0 when every step ran and exited 0.
#   scripts/gpu-bench.sh rehearse [--bundled-libc] [--only LIST]
#       Here: `run --quick` from a fresh folder holding only scripts/gpu-bench.sh and .gpu-pack/,
#       in a private mount namespace where the build tree, the source tree and this machine's copy
#       of every packed library are hidden (an empty file or folder bind-mounted over each), so a
#       library missing from the pack or a path into the build fails here as it would there.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
packdir=$here/.gpu-pack
pack=$packdir/bounce.tar.xz
die() { echo "gpu-bench: $*" >&2; exit 2; }

# ---------------------------------------------------------------------------------------------
# pack (here)

# Libraries every Linux machine has, in versions at least as new as a Debian 12 build needs
# unless the machine is older: they go to sys/, used only with --bundled-libc or when the
# target cannot start bounce with its own.
is_base_lib() {
  case "$1" in
    linux-vdso.so*|ld-linux*|libc.so*|libm.so*|libmvec.so*|libpthread.so*|libdl.so*|librt.so*|libgcc_s.so*|libstdc++.so*) return 0 ;;
    *) return 1 ;;
  esac
}

fetch_gl_debs() {
  # The device tool's README, verbatim in effect: the loader and GL dispatch packages, unpacked
  # into / on the device by the run command.
  if compgen -G "$here/.gl/*.deb" >/dev/null; then return; fi
  local o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
  mkdir -p "$here/.gl" /tmp/amd64/partial
  apt-get "${o[@]}" update >/dev/null
  (cd "$here/.gl" && apt-get "${o[@]}" download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
}

cmd_pack() {
  local build=$here/build/release warm=1
  while [ $# -gt 0 ]; do
    case "$1" in
      --build) build=$(cd "$2" && pwd -P); shift 2 ;;
      --no-warm) warm=0; shift ;;
      *) die "pack: unknown option '$1' (expected --build DIR or --no-warm)" ;;
    esac
  done
  [ -x "$build/bounce" ] || die "pack: $build/bounce: missing (expected a release build: cmake --preset release && cmake --build --preset release)"
  local stage
  stage=$(mktemp -d "${TMPDIR:-/tmp}/gpu-pack.XXXXXX")
  trap 'rm -rf "$stage"' RETURN
  local b=$stage/bounce
  cmake --install "$build" --prefix "$b" --strip >/dev/null
  mkdir -p "$b/lib" "$b/sys"

  # Every library the dynamic linker resolves for bounce, by soname.
  local name path
  while read -r name path; do
    [ "$path" = "not" ] && die "pack: ldd: $name not found"
    if is_base_lib "$name"; then cp -L "$path" "$b/sys/$name"; else cp -L "$path" "$b/lib/$name"; fi
  done < <(ldd "$b/bin/bounce" | awk '$2 == "=>" && $3 != "" { print $1, $3 }')
  cp -L "$(ldd "$b/bin/bounce" | awk '/ld-linux/ && $2 != "=>" { print $1 }')" "$b/sys/ld-linux-x86-64.so.2"
  # TBB loads its scalable allocator with dlopen, which ldd does not see.
  local extra
  for extra in libtbbmalloc.so.2 libtbbmalloc_proxy.so.2; do
    path=$(ldconfig -p | awk -v n="$extra" '$1 == n && /x86-64/ { print $NF; exit }')
    if [ -n "$path" ]; then cp -L "$path" "$b/lib/$extra"; fi
  done

  if [ "$warm" = 1 ]; then
    # Bake what the benchmarks read, with the packed binary itself: cooked assets, probe volumes and
    # the levels' DNRT fields (`bounce bake`), then the DNRT variants' fields (sh=9, grid 16/64,
    # intrusion) through a tiny `bench dnrt` run on lavapipe. Cache keys are content hashes, so
    # they are valid on any machine.
    local lvl
    for lvl in "$b"/share/bounce/content/levels/*.json; do
      BOUNCE_CACHE=$b/cache LD_LIBRARY_PATH=$b/lib "$b/bin/bounce" bake "$lvl" >/dev/null
    done
    BOUNCE_CACHE=$b/cache LD_LIBRARY_PATH=$b/lib MESA_SHADER_CACHE_DIR=$stage/mesa \
      "$b/bin/bounce" bench dnrt --resolution 32x18 --frames 1 >/dev/null
    # cornell-5's RTF fields (its props carry "rtf" components; the level's effects leave rtf out), which
    # the rtf step's profile and bench read.
    BOUNCE_CACHE=$b/cache LD_LIBRARY_PATH=$b/lib "$b/bin/bounce" bake "$b/share/bounce/content/levels/cornell-5.json" \
      --effects direct,shadows,probes,dnrt,rtf >/dev/null
  fi

  mkdir -p "$packdir"
  rm -f "$pack"
  tar -C "$stage" -cf - bounce | xz -T0 -6 >"$pack.tmp"
  mv "$pack.tmp" "$pack"
  fetch_gl_debs
  echo "gpu-bench: $pack: $(du -sm "$pack" | cut -f1) MiB compressed, $(du -sm "$b" | cut -f1) MiB unpacked" \
       "(bin $(du -sm "$b/bin" | cut -f1), lib $(du -sm "$b/lib" | cut -f1), sys $(du -sm "$b/sys" | cut -f1)," \
       "cache $(du -sm "$b/cache" 2>/dev/null | cut -f1 || echo 0) MiB); .gl: $(ls "$here/.gl" | wc -l) packages"
  echo "gpu-bench: libraries packed: $(ls "$b/lib" | tr '\n' ' ')"
}

# ---------------------------------------------------------------------------------------------
# run (there)

# "key=value key=value WxH ..." lines (the bench commands' output) to CSV; a bare WxH token is the
# column "resolution". The header comes from the first line.
kv_to_csv() {
  awk -v pattern="$1" '
    $0 ~ pattern {
      n = 0
      for (i = 1; i <= NF; i++) {
        eq = index($i, "=")
        if (eq) { k[++n] = substr($i, 1, eq - 1); v[n] = substr($i, eq + 1) }
        else if ($i ~ /^[0-9]+x[0-9]+$/) { k[++n] = "resolution"; v[n] = $i }
      }
      if (!header) { line = k[1]; for (i = 2; i <= n; i++) line = line "," k[i]; print line; header = 1 }
      line = v[1]; for (i = 2; i <= n; i++) line = line "," v[i]; print line
    }'
}

cmd_run() {
  local quick=0 only="" budget=300 out=${OUT:-} device=NVIDIA device_set=0 bundled=0
  while [ $# -gt 0 ]; do
    case "$1" in
      --quick) quick=1; shift ;;
      --only) only=",$2,"; shift 2 ;;
      --budget) budget=$2; shift 2 ;;
      --out) out=$2; shift 2 ;;
      --device) device=$2; device_set=1; shift 2 ;;
      --bundled-libc) bundled=1; shift ;;
      *) die "run: unknown option '$1' (expected --quick, --only LIST, --budget S, --out DIR, --device NAME, --bundled-libc)" ;;
    esac
  done
  [ -f "$pack" ] || die "run: $pack: missing (expected scripts/gpu-bench.sh pack, and .gpu-pack in the run tool's carry)"
  [ -n "$out" ] || out=$PWD/gpu-bench-out
  mkdir -p "$out"
  out=$(cd "$out" && pwd -P)
  [ "$quick" = 1 ] && [ "$device_set" = 0 ] && device=""
  local start=$SECONDS deadline=$((SECONDS + budget))
  local log=$out/log.txt
  : >"$log"
  say() { echo "$*" | tee -a "$log"; }

  local work
  work=$(mktemp -d "${TMPDIR:-/tmp}/gpu-bench.XXXXXX")
  xz -dc "$pack" | tar -C "$work" -xf -
  local B=$work/bounce
  # The environment bounce reads: nothing from a build tree or the caller.
  unset BOUNCE_SHADER_DIR BOUNCE_CONTENT BOUNCE_COOK_CACHE BOUNCE_VALIDATION
  export BOUNCE_CACHE=$B/cache MESA_SHADER_CACHE_DIR=$work/mesa LD_LIBRARY_PATH=$B/lib
  if [ -n "$device" ]; then export BOUNCE_DEVICE=$device; else unset BOUNCE_DEVICE; fi
  # The NVIDIA driver's ICD manifest, where the image keeps it outside the loader's search path.
  local icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  if [ -z "${VK_DRIVER_FILES:-}${VK_ICD_FILENAMES:-}" ] && [ -f "$icd" ] && [ "$quick" = 0 ] &&
     ! ls /usr/share/vulkan/icd.d/nvidia_icd.json /etc/vulkan/icd.d/nvidia_icd.json >/dev/null 2>&1; then
    export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd
  fi

  # bounce itself, or through the packed dynamic linker (then /proc/self/exe is sys/ld-linux…, and
  # engine/core/paths.hpp finds <sys>/../share/bounce as it finds <bin>/../share/bounce).
  local bx=$work/bounce-run
  if [ "$bundled" = 0 ] && ! "$B/bin/bounce" --help >/dev/null 2>"$work/start.err"; then
    say "gpu-bench: bounce does not start with this machine's C/C++ runtime ($(head -c 300 "$work/start.err")): using the packed one"
    bundled=1
  fi
  if [ "$bundled" = 1 ]; then
    printf '#!/bin/sh\nexec "%s/sys/ld-linux-x86-64.so.2" --library-path "%s/lib:%s/sys" "%s/bin/bounce" "$@"\n' "$B" "$B" "$B" "$B" >"$bx"
  else
    printf '#!/bin/sh\nexec "%s/bin/bounce" "$@"\n' "$B" >"$bx"
  fi
  chmod +x "$bx"

  {
    echo "== machine"
    date -u; uname -srm; echo "cores: $(nproc)"; head -1 /proc/meminfo
    (ldd --version 2>&1 | head -1) || true
    if command -v nvidia-smi >/dev/null; then
      nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader 2>&1 || true
    else
      echo "no nvidia-smi"
    fi
    echo "system Vulkan loader: $(ldconfig -p | grep -c 'libvulkan.so.1') entries; VK_DRIVER_FILES=${VK_DRIVER_FILES:-unset}"
    echo "ICD manifests: $(ls /usr/share/vulkan/icd.d /etc/vulkan/icd.d 2>/dev/null | tr '\n' ' ')"
    echo "bounce: $([ "$bundled" = 1 ] && echo 'packed C/C++ runtime' || echo "this machine's C/C++ runtime"); BOUNCE_DEVICE=${BOUNCE_DEVICE:-unset}; quick=$quick; budget ${budget}s"
    echo "pack: $(du -sm "$pack" | cut -f1) MiB; cache: $(find "$B/cache" -type f 2>/dev/null | wc -l) files"
  } 2>&1 | tee -a "$log"

  local failed=() ran=0
  wanted() { [ -z "$only" ] || [[ "$only" == *",$1,"* ]]; }
  # step NAME COMMAND...: runs under what is left of the budget, output into the log.
  step() {
    local name=$1; shift
    local left=$((deadline - SECONDS))
    if [ "$left" -le 5 ]; then say "== $name: SKIPPED, budget spent"; failed+=("$name"); return 0; fi
    say "== $name (${left}s left): $*"
    local t0=$SECONDS rc=0
    timeout -k 5 "$left" "$@" 2>&1 | tee -a "$log" || rc=$?
    say "== $name: exit $rc, $((SECONDS - t0)) s"
    ran=$((ran + 1))
    [ "$rc" = 0 ] || failed+=("$name")
  }

  local r1366=1366x768 r720=1280x720 frames=30 levels=() 
  local dnrt_extra=() vlm_extra=(--frames 10 --warmup 2) k_extra=() prof_frames=60
  if [ "$quick" = 1 ]; then
    r1366=137x77 r720=128x72 frames=2 prof_frames=2
    dnrt_extra=(--levels cornell-1,cornell-5 --variant-levels cornell-1)
    vlm_extra=(--frames 1 --warmup 1 --counts 20,240) k_extra=(--counts 10,120)
  fi
  for l in "$B"/share/bounce/content/levels/*.json; do levels+=("$l"); done

  if wanted dnrt1366; then
    step dnrt1366 "$bx" bench dnrt --resolution "$r1366" --frames "$frames" "${dnrt_extra[@]}" --csv "$out/dnrt-1366x768.csv"
  fi
  if wanted dnrt720; then
    step dnrt720 "$bx" bench dnrt --resolution "$r720" --frames "$frames" "${dnrt_extra[@]}" --csv "$out/dnrt-1280x720.csv"
  fi
  if wanted rtf; then
    # Issue 14's "RTF shading per object ≤ DNRT's in the same bounce profile run", on a GPU: both effects on
    # cornell-5's props in one profile (rows "rtf" and "dnrt" per object), then bench rtf at the three shading
    # resolutions (README "RTF at half and quarter resolution, session 25"), on the level's field settings.
    local c5=$B/share/bounce/content/levels/cornell-5.json rtf_frames=$prof_frames
    step rtf-profile "$bx" profile "$c5" --effects direct,shadows,probes,dnrt,rtf --frames "$rtf_frames" \
      --resolution "$r720" --csv "$out/rtf-profile.csv"
    step rtf-bench "$bx" bench rtf --level "$c5" --runs 1 --proxies 8 --spheres 6 --face 6 --rays 8 --vertex-rays 8 \
      --clusters 16 --components 8 --radii 0.5,4 --resolution "$r720" --frames "$frames" --rtf-resolution full,half,quarter
  fi
  if wanted vlm-lights; then
    step vlm-lights "$bx" bench vlm-lights --resolution "$r720" "${vlm_extra[@]}"
  fi
  if wanted vlm-k; then
    local kopt=("${vlm_extra[@]}")
    [ "$quick" = 1 ] && kopt=(--frames 1 --warmup 1 "${k_extra[@]}")
    step vlm-k "$bx" bench vlm-k --resolution "$r720" "${kopt[@]}"
  fi
  if wanted profile; then
    local l
    for l in "${levels[@]}"; do
      step "profile-$(basename "$l" .json)" "$bx" profile "$l" --frames "$prof_frames" --resolution "$r720" \
        --csv "$work/profile-$(basename "$l" .json).csv"
    done
  fi
  if wanted vlm-grid; then
    # Thesis Table 5.2's rows as the README's lavapipe table has them; the gather build only where it
    # finishes in seconds, and the 100k x 50^3 gather (53 s on 2 cores) last.
    local rows=("10000 10" "50000 10" "100000 10" "10000 50" "50000 50 --no-gather" "100000 50 --no-gather"
                "10000 100 --no-gather" "100000 100 --no-gather" "100000 50")
    [ "$quick" = 1 ] && rows=("1000 10" "2000 20 --no-gather")
    local row
    for row in "${rows[@]}"; do
      set -- $row
      local lights=$1 grid=$2; shift 2
      step "vlm-grid-$lights-$grid${1:+-nogather}" "$bx" bench vlm-grid --lights "$lights" --grid "$grid" --runs 3 "$@"
    done
  fi

  # CSVs from the printed lines (the commands that have no --csv) and the per-level profiles.
  kv_to_csv '^lights=[0-9]+ .*vlm_ms=' <"$log" >"$out/vlm-lights.csv"
  kv_to_csv '^k=[0-9]+ .*vlm_ms=' <"$log" >"$out/vlm-k.csv"
  kv_to_csv '^lights=[0-9]+ .*scatter_ms=' <"$log" >"$out/vlm-grid.csv"
  # bench rtf's scene lines carry both the render size (bare WxH, kv_to_csv's "resolution") and the shading
  # resolution ("resolution=full|half|quarter"): the latter becomes "shading".
  sed -E 's/ resolution=(full|half|quarter)/ shading=\1/' "$log" | kv_to_csv '^objects=[0-9]+ .*rtf_ms=' >"$out/rtf-scenes.csv"
  kv_to_csv '^object=[^ ]+ .*compressed_mb=' <"$log" >"$out/rtf-objects.csv"
  local csv first=1
  : >"$out/profile.csv"
  for csv in "$work"/profile-*.csv; do
    [ -f "$csv" ] || continue
    local name
    name=$(basename "$csv" .csv); name=${name#profile-}
    if [ "$first" = 1 ]; then echo "level,$(head -1 "$csv")" >>"$out/profile.csv"; first=0; fi
    tail -n +2 "$csv" | sed "s/^/$name,/" >>"$out/profile.csv"
  done
  for csv in "$out"/*.csv; do [ -s "$csv" ] || rm -f "$csv"; done

  say "gpu-bench: $ran steps ran in $((SECONDS - start)) s; failed or skipped: ${failed[*]:-none}; files: $(cd "$out" && ls | tr '\n' ' ')"
  rm -rf "$work"
  [ "${#failed[@]}" = 0 ]
}

# ---------------------------------------------------------------------------------------------
# rehearse (here)

cmd_rehearse() {
  [ -f "$pack" ] || die "rehearse: $pack: missing (expected scripts/gpu-bench.sh pack first)"
  unshare -rm true 2>/dev/null || die "rehearse: unshare -rm is not permitted here (expected a kernel with user namespaces)"
  local fresh
  fresh=$(mktemp -d "${TMPDIR:-/tmp}/gpu-rehearse.XXXXXX")
  mkdir -p "$fresh/repo/scripts" "$fresh/empty"
  : >"$fresh/empty-file"
  cp "$here/scripts/gpu-bench.sh" "$fresh/repo/scripts/"
  cp -r "$packdir" "$fresh/repo/.gpu-pack"
  # This machine's copies of the packed libraries (lib/ only: sys/ is this machine's own runtime).
  local hide=() name path
  while read -r name; do
    for path in /lib/x86_64-linux-gnu/"$name" /usr/lib/x86_64-linux-gnu/"$name"; do
      [ -e "$path" ] && hide+=("$(readlink -f "$path")")
    done
  done < <(xz -dc "$pack" | tar -tf - | sed -n 's|^bounce/lib/\([^/]\+\)$|\1|p')
  local build
  build=$(cd "$here/build" 2>/dev/null && pwd -P || echo "")
  echo "gpu-bench: rehearsal in $fresh/repo, hiding ${#hide[@]} system libraries, ${build:-no build dir} and $here"
  local rc=0
  (cd "$fresh/repo" && OUT="$fresh/out" unshare -rm bash -c '
      set -e
      empty=$1 emptyfile=$2 build=$3 src=$4; shift 4
      while [ "$1" != "--" ]; do mount --bind "$emptyfile" "$1"; shift; done; shift
      [ -n "$build" ] && mount --bind "$empty" "$build"
      mount --bind "$empty" "$src"
      exec scripts/gpu-bench.sh run --quick "$@"
    ' sh "$fresh/empty" "$fresh/empty-file" "$build" "$here" "${hide[@]}" -- "$@") || rc=$?
  echo "gpu-bench: rehearsal exit $rc; results in $fresh/out"
  return $rc
}

case "${1:-}" in
  pack) shift; cmd_pack "$@" ;;
  run) shift; cmd_run "$@" ;;
  rehearse) shift; cmd_rehearse "$@" ;;
  *) die "usage: scripts/gpu-bench.sh pack|run|rehearse [options] (see the comment at the top)" ;;
esac
