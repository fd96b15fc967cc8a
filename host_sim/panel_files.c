/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where the panel's page lives. The same rcxsim binary runs from the build tree, from an unpacked package and
 * installed: first ../share/openrcx/panel next to the executable (bin/rcxsim -> share/openrcx/panel, as `make
 * install` and the Debian package lay it out, under whatever prefix), then the source tree it was built from.
 */
#include <limits.h>
#include <pthread.h>
#include "panel.h"
#include "share_dir.h"

static char dir[PATH_MAX];
static pthread_once_t found = PTHREAD_ONCE_INIT;

static void find(void)
{
    share_dir_find("panel", "index.html", RCXSIM_PANEL_FILES, dir, sizeof dir);
}

/* The HTTP threads ask for it; the first call decides, once. */
const char *panel_files_dir(void)
{
    pthread_once(&found, find);
    return dir;
}
