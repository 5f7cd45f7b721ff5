#!/usr/bin/env bash
# Install the Debian libraries that Qt (offscreen and xcb), open3d and the PDF checks need.
# Only missing packages are installed; nothing happens when all are present.
set -euo pipefail
PACKAGES=(
  libusb-1.0-0 libegl1 libgl1 libgl1-mesa-dri libxkbcommon0 libxkbcommon-x11-0
  libfontconfig1 libdbus-1-3 fonts-dejavu-core fonts-wqy-zenhei poppler-utils xvfb xauth
  libxcb-cursor0 libxcb-icccm4 libxcb-keysyms1 libxcb-image0 libxcb-render-util0
  libxcb-xkb1 libxcb-shape0 libxcb-randr0 libxcb-xinerama0
)
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
if ! command -v apt-get >/dev/null; then
  echo "warning: not a Debian system; install the equivalents of: ${missing[*]}" >&2
  exit 0
fi
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "installing system packages: ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
