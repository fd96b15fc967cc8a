# SPDX-License-Identifier: MPL-2.0
# Sourced by the package tests. CTest sets DEB (the package package.build made), VERSION (the project's),
# DPKG_DEB, NQC, LINTIAN, PACKAGE_DIR (this folder) and PACKAGE_TMP (a scratch folder in the build tree). The
# scratch folder WORK, SIM_PID's cleanup and fail() are the end-to-end tests'.
E2E_TMP="$PACKAGE_TMP"
. "$PACKAGE_DIR/../e2e/lib.sh"
[ -f "$DEB" ] || fail "no package $DEB (package.build makes it; make deb)"
