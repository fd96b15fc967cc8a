/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where the panel's page lives. The same rcxsim binary runs from the build tree, from an unpacked package and
 * installed: first ../share/openrcx/panel next to the executable (bin/rcxsim -> share/openrcx/panel, as `make
 * install` and the Debian package lay it out, under whatever prefix), then the source tree it was built from.
 */
#define _POSIX_C_SOURCE 200809L
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include "panel.h"

static char dir[PATH_MAX];
static pthread_once_t found = PTHREAD_ONCE_INIT;

static void find(void)
{
    static const char rel[] = "/../share/openrcx/panel";
    char exe[PATH_MAX], index[PATH_MAX + sizeof rel + sizeof "/index.html"];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = NULL;

    if (n > 0) {
        exe[n] = 0;
        slash = strrchr(exe, '/');
    }
    if (slash) {
        *slash = 0;
        snprintf(index, sizeof index, "%s%s/index.html", exe, rel);
        if (access(index, R_OK) == 0 && strlen(exe) + sizeof rel <= sizeof dir) {
            snprintf(dir, sizeof dir, "%s%s", exe, rel);
            return;
        }
    }
    snprintf(dir, sizeof dir, "%s", RCXSIM_PANEL_FILES);
}

/* The HTTP threads ask for it; the first call decides, once. */
const char *panel_files_dir(void)
{
    pthread_once(&found, find);
    return dir;
}
