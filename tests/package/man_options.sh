#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# rcxsim(1)'s OPTIONS section documents exactly the options `rcxsim --help` lists, no more, no fewer. Both lists
# are read the same way: each entry's tag (a line that starts, indented, with "-"; "-h, --help" counts twice).
#   man_options.sh <rcxsim> <groff> <rcxsim.1>
set -eu
rcxsim="$1" groff="$2" page="$3"
tags() { # the options that begin indented lines, one per line, sorted
    awk '/^[ \t]+-/ { for (i = 1; i <= NF; i++) { o = $i; more = sub(/,$/, "", o); sub(/=.*/, "", o); print o; if (!more) break } }' |
        sort -u
}
help=$("$rcxsim" --help | tags)
man=$(LC_ALL=C "$groff" -man -Tascii -P-cbou "$page" 2>/dev/null |
      awk '/^[A-Z]/ { in_opts = ($0 == "OPTIONS") ; next } in_opts && /^       -/' | tags)
[ -n "$help" ] || { echo "FAIL: no options in rcxsim --help"; exit 1; }
[ -n "$man" ] || { echo "FAIL: no options in the OPTIONS section of $page"; exit 1; }
missing=$(printf '%s\n' "$help" | grep -vxF -e "$man" || true)
extra=$(printf '%s\n' "$man" | grep -vxF -e "$help" || true)
[ -z "$missing" ] || echo "FAIL: rcxsim --help lists, $page does not document:" $missing
[ -z "$extra" ] || echo "FAIL: $page documents, rcxsim --help does not list:" $extra
[ -z "$missing$extra" ] || exit 1
echo "OK: the same" $(printf '%s\n' "$help" | wc -l) "options:" $help
