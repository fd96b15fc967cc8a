/* SPDX-License-Identifier: MPL-2.0 */
/* See share_dir.h. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "share_dir.h"

void share_dir_find(const char *sub, const char *probe, const char *source, char *dir, size_t size)
{
    char exe[PATH_MAX], path[2 * PATH_MAX], real[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = NULL;

    if (n > 0) {
        exe[n] = 0;
        slash = strrchr(exe, '/');
    }
    if (slash) {
        *slash = 0;
        snprintf(path, sizeof path, "%s/../share/openrcx/%s/%s", exe, sub, probe);
        if (access(path, R_OK) == 0) {
            snprintf(path, sizeof path, "%s/../share/openrcx/%s", exe, sub);
            /* .../share/openrcx/sub rather than .../bin/../share: messages name it */
            const char *found = realpath(path, real) ? real : path;
            if (strlen(found) < size) {
                snprintf(dir, size, "%s", found);
                return;
            }
        }
    }
    snprintf(dir, size, "%s", source);
}
