# Sourced by the package tests. CTest sets DEB (the package package.build made), VERSION (the project's),
# DPKG_DEB, NQC, LINTIAN, PACKAGE_DIR (this folder) and PACKAGE_TMP (a scratch folder in the build tree).
set -eu
WORK=$(mktemp -d "${PACKAGE_TMP:-/tmp}/$(basename "$0" .sh).XXXXXX")
SIM_PID=""
cleanup() {
    if [ -n "$SIM_PID" ]; then
        kill "$SIM_PID" 2>/dev/null || true
        wait "$SIM_PID" 2>/dev/null || true
    fi
    rm -rf "$WORK"
}
trap cleanup EXIT
trap 'exit 1' INT TERM
fail() {
    echo "FAIL: $*" >&2
    [ ! -f "$WORK/sim.err" ] || cat "$WORK/sim.err" >&2
    exit 1
}
[ -f "$DEB" ] || fail "no package $DEB (package.build makes it; make deb)"
