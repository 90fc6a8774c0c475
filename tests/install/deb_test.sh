#!/usr/bin/env bash
# The Debian package of `make deb`, unpacked into a scratch root with dpkg -x (not installed):
# it holds every part, declares its dependencies, and its CLI, Python module and GStreamer
# element run from there.
# Usage: deb_test.sh PACKAGE.deb
set -euo pipefail

deb=$(realpath "$1")
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
libdir=usr/lib/$multiarch
python_dir=usr/lib/python3/dist-packages

depends=$(dpkg-deb --field "$deb" Depends)
for package in libopencv-core libgstreamer1.0-0 libc6 python3-numpy python3-opencv; do
  [[ $depends == *"$package"* ]] || fail "Depends lacks $package: $depends"
done

dpkg -x "$deb" "$root"
for file in usr/bin/movseg usr/include/movseg/segmenter.h "$libdir/libmovseg.so.0" \
    "$libdir/libmovseg.a" "$libdir/cmake/movseg/movseg-config.cmake" \
    "$libdir/pkgconfig/movseg.pc" "$libdir/gstreamer-1.0/libgstmovseg.so" \
    "$python_dir/movseg/__init__.py" "$python_dir/movseg/__init__.pyi" "$python_dir/movseg/py.typed"; do
  [ -e "$root/$file" ] || fail "the package lacks /$file"
done

cli=$root/usr/bin/movseg
"$cli" synth -o "$root/clip" --frames 4 --size 96x72 >/dev/null
"$cli" segment "$root/clip/frames" -o "$root/masks" -q
[ "$(ls "$root/masks"/*.png | wc -l)" -eq 4 ] || fail "the packaged CLI did not write 4 masks"

python() { PYTHONPATH=$root/$python_dir PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 "$@"; }
[ "$(python -c 'import movseg.__main__ as m; print(m.cli_path())')" = "$cli" ] ||
  fail "the packaged module does not run the packaged CLI"
module_version=$(python -c 'import movseg; print("movseg", movseg.__version__)')
[ "$module_version" = "$("$cli" --version)" ] || fail "$module_version, but $("$cli" --version)"
python -m movseg segment "$root/clip/frames" -o "$root/masks-python" -q
# The module passes its arguments on: the same masks, of which the last shows the movers.
last_mask=$root/masks/00003.png
/usr/bin/python3 -c "import cv2, sys; sys.exit(cv2.countNonZero(cv2.imread(sys.argv[1], 0)) == 0)" \
  "$last_mask" || fail "the packaged CLI found nothing moving on the clip's last frame"
for mask in "$root/masks"/*.png; do
  cmp -s "$mask" "$root/masks-python/$(basename "$mask")" ||
    fail "python -m movseg wrote another $(basename "$mask") than the CLI"
done

GST_PLUGIN_PATH=$root/$libdir/gstreamer-1.0 GST_REGISTRY=$root/registry.bin \
  gst-inspect-1.0 movseg >/dev/null || fail "gst-inspect-1.0 does not find the packaged element"
echo "ok: $(basename "$deb") ($module_version)"
