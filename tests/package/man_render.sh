#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Each man page renders with no warning, through groff (all warnings on) and through man-db as man(1) shows it.
#   man_render.sh <groff> <man> <page>...
set -u
groff="$1" man="$2"
shift 2
status=0
for page in "$@"; do
    out=$("$groff" -ww -man -z "$page" 2>&1)
    [ -z "$out" ] || { echo "FAIL: groff -ww on $page:"; echo "$out"; status=1; }
    out=$(LC_ALL=C.UTF-8 MANWIDTH=80 "$man" --warnings -E UTF-8 -l "$page" 2>&1 >/dev/null)
    [ -z "$out" ] || { echo "FAIL: man --warnings on $page:"; echo "$out"; status=1; }
    [ $status = 0 ] && echo "OK: $page"
done
exit $status
