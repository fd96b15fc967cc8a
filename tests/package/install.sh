#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# `make install` (cmake --install, DESTDIR and a prefix) installs the same files as the package, and that rcxsim
# finds the installed panel: the installed copy is marked, and the page served carries the mark.
. "$PACKAGE_DIR/lib.sh"
DESTDIR="$WORK/dest" "$CMAKE" --install "$BUILD_DIR" --prefix /usr >/dev/null || fail "cmake --install failed"
(cd "$WORK/dest" && find . -type f | sort) >"$WORK/installed"
"$DPKG_DEB" -c "$DEB" | awk '$1 ~ /^-/ { print $6 }' | sort >"$WORK/packaged"
diff "$WORK/packaged" "$WORK/installed" || fail "make install and the package differ (< package, > install)"
sim="$WORK/dest/usr/bin/rcxsim"
mark="<!-- installed copy $$ -->"
echo "$mark" >>"$WORK/dest/usr/share/openrcx/panel/index.html"
timeout 60 "$sim" --panel 0 >"$WORK/sim.out" 2>"$WORK/sim.err" &
SIM_PID=$!
n=0
until grep -q 'panel at http://127.0.0.1:' "$WORK/sim.err"; do
    n=$((n + 1))
    [ $n -lt 200 ] || fail "rcxsim did not start"
    sleep 0.05
done
url=$(sed -n 's/.*panel at \(http:[^ ]*\/\).*/\1/p' "$WORK/sim.err" | head -n 1)
page=$(curl -sf --max-time 10 "$url") || fail "GET $url failed"
case "$page" in *"$mark"*) ;; *) fail "the installed rcxsim did not serve the installed page" ;; esac
echo "OK: $(wc -l <"$WORK/installed") files, as in the package; the installed panel served"
