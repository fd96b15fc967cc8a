#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# Debian's package checker finds no error in the package (README.md lists the warnings kept, and why).
. "$PACKAGE_DIR/lib.sh"
command -v "$LINTIAN" >/dev/null 2>&1 || fail "lintian is not installed (make installs it)"
"$LINTIAN" --fail-on error --display-level '>=warning' "$DEB" >"$WORK/out" 2>&1 && status=0 || status=$?
cat "$WORK/out"
[ $status = 0 ] || fail "lintian: status $status"
if grep -q '^E: ' "$WORK/out"; then fail "lintian reports errors"; fi
echo "OK: no lintian error"
