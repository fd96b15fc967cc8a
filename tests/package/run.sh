#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The package works from wherever it is unpacked: dpkg-deb -x into a scratch folder, then that folder's rcxsim runs
# a brick on a pseudo-terminal with its panel; the real nqc downloads and starts a program; the panel's page (read
# from the unpacked files, not the source tree: a mark is added to the unpacked copy) and /state answer.
. "$PACKAGE_DIR/lib.sh"
root="$WORK/root"
"$DPKG_DEB" -x "$DEB" "$root"
sim="$root/usr/bin/rcxsim"
[ "$("$sim" --version)" = "rcxsim (OpenRCX) $VERSION" ] || fail "--version: $("$sim" --version)"
# The shipped scenes are found in the unpacked tree: one runs, and a copy broken there is the one refused.
"$sim" --world testpad --fast --duration 100 || fail "--world testpad from the package failed"
echo '{}' >"$root/usr/share/openrcx/scenes/maze.json"
"$sim" --world maze --fast --duration 100 2>"$WORK/maze.err" && fail "the unpacked maze.json was not the one read"
grep -qF "$root/usr/share/openrcx/scenes/maze.json" "$WORK/maze.err" || fail "--world maze: $(cat "$WORK/maze.err")"
mark="<!-- unpacked copy $$ -->"
echo "$mark" >>"$root/usr/share/openrcx/panel/index.html"

timeout 120 "$sim" --tty "$WORK/rcx" --panel 0 >"$WORK/sim.out" 2>"$WORK/sim.err" &
SIM_PID=$!
n=0
until [ -e "$WORK/rcx" ] && grep -q 'panel at http://127.0.0.1:' "$WORK/sim.err"; do
    n=$((n + 1))
    [ $n -lt 200 ] || fail "rcxsim did not start"
    kill -0 "$SIM_PID" 2>/dev/null || fail "rcxsim exited"
    sleep 0.05
done
url=$(sed -n 's/.*panel at \(http:[^ ]*\/\).*/\1/p' "$WORK/sim.err" | head -n 1)

cat >"$WORK/prog.nqc" <<'NQC'
task main()
{
    SetUserDisplay(Timer(0), 0);
    OnFwd(OUT_A);
    OnRev(OUT_C);
    while (true) Wait(100);
}
NQC
timeout 60 "$NQC" -S"$WORK/rcx" -TRCX2 -d -pgm 3 "$WORK/prog.nqc" -run || fail "nqc -d -pgm 3 -run failed"

page=$(curl -sf --max-time 10 "$url") || fail "GET $url failed"
case "$page" in *"$mark"*) ;; *) fail "the page was not read from the unpacked package" ;; esac
state=""
n=0
while :; do
    state=$(curl -sf --max-time 10 "${url}state") || fail "GET ${url}state failed"
    case "$state" in *'"A":{"dir":"fwd","level":7}'*'"C":{"dir":"rev","level":7}'*'"slot":3'*) break ;; esac
    n=$((n + 1))
    [ $n -lt 50 ] || fail "program not running: $state"
    sleep 0.1
done
echo "OK: $sim ran the program; $url and /state answered"
