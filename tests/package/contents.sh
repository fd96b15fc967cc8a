#!/bin/sh
# SPDX-License-Identifier: MPL-2.0
# The package holds the files the issue lists, under /usr, and its control fields are what they must be.
. "$PACKAGE_DIR/lib.sh"
case "$(basename "$DEB")" in
"openrcx_${VERSION}_$(dpkg --print-architecture).deb") ;;
*) fail "package file $(basename "$DEB") is not openrcx_${VERSION}_<arch>.deb" ;;
esac
field() { "$DPKG_DEB" -f "$DEB" "$1"; }
[ "$(field Package)" = openrcx ] || fail "Package: $(field Package)"
[ "$(field Version)" = "$VERSION" ] || fail "Version: $(field Version), expected $VERSION"
[ "$(field Recommends)" = nqc ] || fail "Recommends: $(field Recommends)"
[ "$(field Suggests)" = brickos ] || fail "Suggests: $(field Suggests)"
# shlibdeps: the C library and libmicrohttpd, with versions, from the binary
field Depends | grep -q 'libc6 (>= ' || fail "Depends lacks libc6: $(field Depends)"
field Depends | grep -q 'libmicrohttpd[0-9]* (>= ' || fail "Depends lacks libmicrohttpd: $(field Depends)"
for lib in libchipmunk libcjson libpng; do # the world (--world)
    field Depends | grep -q "$lib[0-9.-]* (>= " || fail "Depends lacks $lib: $(field Depends)"
done
"$DPKG_DEB" -c "$DEB" | awk '{ print $1, $6 }' >"$WORK/list"
for f in ./usr/bin/rcxsim ./usr/share/openrcx/openrcx.srec ./usr/share/openrcx/openrcx.lgo \
    ./usr/share/openrcx/panel/index.html ./usr/share/openrcx/panel/panel.js ./usr/share/openrcx/panel/panel.css \
    ./usr/share/openrcx/panel/brick.svg ./usr/share/openrcx/panel/world.js \
    ./usr/share/man/man1/rcxsim.1.gz ./usr/share/man/man7/openrcx.7.gz \
    ./usr/share/doc/openrcx/README.md ./usr/share/doc/openrcx/README.Debian ./usr/share/doc/openrcx/copyright \
    ./usr/share/doc/openrcx/changelog.gz ./usr/share/doc/openrcx/world.md \
    ./usr/share/openrcx/scenes/testpad.json ./usr/share/openrcx/scenes/testpad.png \
    ./usr/share/openrcx/scenes/arena.json ./usr/share/openrcx/scenes/maze.json \
    ./usr/share/openrcx/scenes/two_robots.json ./usr/share/openrcx/scenes/paper.png; do
    grep -q " $f\$" "$WORK/list" || fail "$f missing from the package"
done
grep -q '^-rwxr-xr-x ./usr/bin/rcxsim$' "$WORK/list" || fail "rcxsim is not 0755"
# Nothing outside /usr, nothing of the build tree
if grep -v ' \./usr/\| \./$\| \./usr$' "$WORK/list"; then fail "files outside /usr"; fi
# The man pages name the version
"$DPKG_DEB" -x "$DEB" "$WORK/root"
for p in man1/rcxsim.1.gz man7/openrcx.7.gz; do
    gzip -dc "$WORK/root/usr/share/man/$p" | grep -q "^\.TH .*\"OpenRCX $VERSION\"" || fail "$p: no version $VERSION"
done
# README.Debian speaks of the installed paths, not of a build tree's (issue 23 §4)
rd="$WORK/root/usr/share/doc/openrcx/README.Debian"
for p in /usr/bin/rcxsim /usr/share/openrcx/openrcx.lgo /usr/share/openrcx/panel/ 'man rcxsim'; do
    grep -q -F -- "$p" "$rd" || fail "README.Debian does not name $p"
done
if grep -n 'build/' "$rd"; then fail "README.Debian names build paths"; fi
# The firmware image is the one `make firmware` built, and carries the version
cmp -s "$WORK/root/usr/share/openrcx/openrcx.srec" "$WORK/root/usr/share/openrcx/openrcx.lgo" ||
    fail "openrcx.srec and openrcx.lgo differ"
echo "OK: $(wc -l <"$WORK/list") entries; Depends: $(field Depends)"
