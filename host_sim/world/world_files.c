/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where the shipped scenes live: ../share/openrcx/scenes next to the executable (installed, or a package unpacked
 * anywhere), else the source tree rcxsim was built from - the same search as the panel's page (panel_files.c).
 */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "world.h"

static char dir[PATH_MAX];
static pthread_once_t found = PTHREAD_ONCE_INIT;

static void find(void)
{
    static const char rel[] = "/../share/openrcx/scenes";
    char exe[PATH_MAX], probe[PATH_MAX + sizeof rel + sizeof "/testpad.json"];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = NULL;

    if (n > 0) {
        exe[n] = 0;
        slash = strrchr(exe, '/');
    }
    if (slash) {
        *slash = 0;
        snprintf(probe, sizeof probe, "%s%s/testpad.json", exe, rel);
        if (access(probe, R_OK) == 0 && strlen(exe) + sizeof rel <= sizeof dir) {
            snprintf(probe, sizeof probe, "%s%s", exe, rel);
            if (!realpath(probe, dir)) /* .../share/openrcx/scenes, not .../bin/../share: messages name it */
                snprintf(dir, sizeof dir, "%s%s", exe, rel);
            return;
        }
    }
    snprintf(dir, sizeof dir, "%s", RCXSIM_SCENES);
}

const char *world_scenes_dir(void)
{
    pthread_once(&found, find);
    return dir;
}
