#!/usr/bin/env bash
# The Debian package on a clean Debian 12: debootstrap a minimal bookworm into a chroot,
# `apt install` the package there (its declared dependencies only), run rfseek-sim from
# it, build examples/downstream against it, then remove it. Needs root and the network
# (deb.debian.org); takes a few minutes, most of it downloading GNU Radio.
#
#   bash scripts/package_deb.sh && sudo bash scripts/check_deb.sh [DEB] [CHROOT]
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
deb=${1:-$(ls "$here"/build-deb/gr-rfseek_*.deb | tail -1)}
root=${2:-/tmp/rfseek-deb12}
mirror=${RFSEEK_DEBIAN_MIRROR:-http://deb.debian.org/debian}

if [ "$(id -u)" -ne 0 ]; then
    echo "check_deb.sh: needs root (debootstrap, chroot)" >&2
    exit 1
fi
command -v debootstrap >/dev/null || apt-get install -y -q debootstrap

if [ ! -x "$root/usr/bin/apt-get" ]; then
    echo "==> debootstrap bookworm into $root"
    debootstrap --variant=minbase bookworm "$root" "$mirror" >"$root.log" 2>&1 ||
        {
            tail -20 "$root.log"
            exit 1
        }
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
mountpoint -q "$root/proc" || mount -t proc proc "$root/proc"
trap 'umount "$root/proc" 2>/dev/null || true' EXIT
cp "$deb" "$root/root/"
name=$(basename "$deb")

in_root() { chroot "$root" env DEBIAN_FRONTEND=noninteractive HOME=/root bash -c "$1"; }

echo "==> apt install ./$name"
in_root "apt-get update -q >/dev/null && apt-get install -y -q /root/$name >/tmp/apt.log 2>&1 ||
    { tail -30 /tmp/apt.log; exit 1; }"
echo "==> rfseek-sim from the package"
in_root "cd /tmp && rfseek-sim --seed 2 --out /tmp/seek | tail -2 && ls /tmp/seek"
in_root "python3 -c 'from gnuradio import rfseek; print(\"gnuradio.rfseek\", rfseek.__version__, rfseek.__file__)'"
echo "==> examples/downstream against the package (with gnuradio-dev, cmake, g++)"
in_root "apt-get install -y -q --no-install-recommends gnuradio-dev cmake g++ make pkg-config >/tmp/apt-dev.log 2>&1 ||
    { tail -30 /tmp/apt-dev.log; exit 1; }
    rm -rf /tmp/downstream &&
    cmake -S /usr/share/gr-rfseek/examples/downstream -B /tmp/downstream >/tmp/ds.log 2>&1 &&
    cmake --build /tmp/downstream >>/tmp/ds.log 2>&1 || { tail -30 /tmp/ds.log; exit 1; }
    /tmp/downstream/seek_report 3 paper 2>/dev/null"
echo "==> apt remove gr-rfseek"
in_root "apt-get remove -y -q gr-rfseek >/dev/null && ! test -e /usr/bin/rfseek-sim &&
    ! test -e /usr/lib/x86_64-linux-gnu/libgnuradio-rfseek.so.0.1 && echo removed"
echo "==> $name: installs, runs, builds downstream, removes on a clean Debian 12"
