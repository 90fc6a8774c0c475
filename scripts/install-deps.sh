#!/usr/bin/env bash
# Installs the Debian packages movseg needs to build, test and run.
# Idempotent: when every package is already installed it does nothing (no apt-get call at all).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libopencv-dev libopencv-contrib-dev   # images, video I/O, pyramids, Lucas-Kanade, MOG2
  libavformat-dev libavcodec-dev libswscale-dev libavutil-dev  # video decoding (src/io/)
  zlib1g-dev                            # PNG chunks checked before libpng sees them (src/io/)
  libjpeg-dev libpng-dev                # frames decoded with their warnings caught (src/io/)
  ffmpeg                                # the tests make damaged and size-changing videos
  libcli11-dev                          # command-line parsing
  nlohmann-json3-dev                    # --stats / --json output
  libboost-graph-dev                    # Boykov-Kolmogorov max-flow
  libeigen3-dev                         # cv::eigen's solver, called on fixed-size storage
  libgtest-dev libgmock-dev             # unit tests
  libbenchmark-dev                      # bench/
  pybind11-dev python3-dev python3-numpy python3-opencv python3-pytest  # Python module
  python3-mypy                          # checks the Python type stubs
  python3-distributed                   # python3 -m movseg batch (Dask)
  libgstreamer1.0-dev libgstreamer-plugins-base1.0-dev  # the GStreamer element
  gstreamer1.0-tools gstreamer1.0-plugins-base gstreamer1.0-plugins-good  # ... and its tests
  python3-gi gir1.2-gstreamer-1.0       # ... one of which drives a pipeline from Python
  chromium                              # renders the HTML report in its test
  dpkg-dev fakeroot file                # make deb (CPack: dpkg-shlibdeps)
  clang libclang-rt-14-dev              # libFuzzer and sanitizer runtimes
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
# npm installs the HTML report's charting library into the build tree (report/package.json).
# Any npm will do: NodeSource's nodejs package carries its own, Debian's is the npm package.
command -v npm >/dev/null || missing+=(npm)

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
