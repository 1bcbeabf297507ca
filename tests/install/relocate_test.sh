#!/bin/sh
# relocate_test.sh CMAKE BUILD_DIR SOURCE_DIR
#
# Installs the build into a temporary prefix, moves the prefix, and runs a tiny `bounce capture`
# from the moved copy with the build and source trees out of reach. Renaming the build tree away is
# impossible while ctest runs from it, so the capture runs in a private mount namespace
# (`unshare -rm`: an unprivileged user namespace) in which an empty folder is bind-mounted over the
# build tree and over the source tree: every path under them, compiled in or derived, finds nothing
# there, while the rest of the machine (the Vulkan loader, lavapipe, the validation layers) is as
# usual. Asserts: the capture exits 0, wrote the captured frames as PNG and PFM of the requested
# size, kept its caches under $XDG_CACHE_HOME/bounce (the installed layout's default), and printed
# no path under either tree.
set -eu
cmake=$1
build=$(cd "$2" && pwd -P)
src=$(cd "$3" && pwd -P)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bounce-relocate.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "relocate_test: $*" >&2; exit 1; }

if ! unshare -rm true 2>/dev/null; then
  echo "relocate_test: SKIPPED: unshare -rm (user + mount namespace) is not permitted here" >&2
  exit 77
fi

"$cmake" --install "$build" --prefix "$tmp/first" >"$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install failed"; }
mv "$tmp/first" "$tmp/moved"
prefix=$tmp/moved
for f in bin/bounce share/bounce/shaders/test/fill.comp.spv share/bounce/content/levels/cornell-1.json \
         share/bounce/tools/plot_accuracy.py share/doc/bounce/README.md; do
  [ -f "$prefix/$f" ] || fail "not installed: $f"
done

mkdir "$tmp/empty" "$tmp/run"
# Sanitizer builds: LeakSanitizer reads its suppressions at exit, when the source tree is hidden, so it
# reads a copy (CMakeLists.txt says why).
if [ -n "${BOUNCE_LSAN_SUPP:-}" ]; then
  cp "$BOUNCE_LSAN_SUPP" "$tmp/lsan.supp"
  LSAN_OPTIONS="suppressions=$tmp/lsan.supp:print_suppressions=0"
  export LSAN_OPTIONS
fi
cd "$tmp/run"
# The build tree first: when it lies inside the source tree, hiding the source tree hides it too,
# and its path would no longer exist to mount over.
status=0
env -u BOUNCE_SHADER_DIR -u BOUNCE_CONTENT -u BOUNCE_CACHE -u BOUNCE_COOK_CACHE \
    XDG_CACHE_HOME="$tmp/xdg" MESA_SHADER_CACHE_DIR="$tmp/mesa" \
    unshare -rm sh -c '
      mount --bind "$1" "$2" && mount --bind "$1" "$3" || exit 90
      for d in "$2" "$3"; do [ ! -e "$d" ] || [ -z "$(ls -A "$d")" ] || exit 91; done
      exec "$4/bin/bounce" capture "$4/share/bounce/content/captures/cornell-1.json" --resolution 40x30 --out "$5"
    ' sh "$tmp/empty" "$build" "$src" "$prefix" "$tmp/out" >"$tmp/capture.log" 2>&1 || status=$?
cat "$tmp/capture.log"
[ $status -ne 90 ] || fail "could not bind-mount over the trees"
[ $status -ne 91 ] || fail "the trees were still visible after the bind mounts"
[ $status -eq 0 ] || fail "bounce capture exited $status"

for frame in 0000 0060; do
  [ -s "$tmp/out/frame-$frame.png" ] || fail "no frame-$frame.png"
  header=$(head -c 9 "$tmp/out/frame-$frame.pfm" | tr '\n' ' ')
  [ "$header" = "PF 40 30 " ] || fail "frame-$frame.pfm header '$header' (expected 'PF 40 30 ')"
done
[ -n "$(ls -A "$tmp/xdg/bounce/cooked" 2>/dev/null)" ] || fail "no cooked assets under \$XDG_CACHE_HOME/bounce/cooked"
if grep -F -e "$build" -e "$src" "$tmp/capture.log" >/dev/null; then fail "the output names a path under the build or source tree"; fi
echo "relocate_test: OK: capture from $prefix wrote frames 0 and 60 (40x30), caches under \$XDG_CACHE_HOME/bounce"
