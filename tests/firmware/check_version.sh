#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The download carries "OpenRCX <version>" for people to read (drivers/CMakeLists.txt), NUL on both sides, and the
# image as it runs does not: the text costs no program memory.
#   check_version.sh <objcopy> <openrcx.srec> <openrcx.bin> <version>
set -eu
objcopy="$1" srec="$2" bin="$3" version="$4"
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
"$objcopy" -I srec -O binary "$srec" "$tmp"
n=$(tr '\0' '\n' <"$tmp" | grep -c -x -F "OpenRCX $version" || true)
[ "$n" = 1 ] || { echo "FAIL: $srec holds \"OpenRCX $version\" $n times, expected once" >&2; exit 1; }
if grep -q -a -F "OpenRCX" "$bin"; then
    echo "FAIL: the running image $bin holds the version text (it must stay in the unpacker's bytes)" >&2
    exit 1
fi
echo "OK: \"OpenRCX $version\" in the download, not in the running image"
