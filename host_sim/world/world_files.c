/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where the shipped scenes live: ../share/openrcx/scenes next to the executable (installed, or a package unpacked
 * anywhere), else the source tree rcxsim was built from - the same search as the panel's page (share_dir.h).
 */
#include <limits.h>
#include <pthread.h>
#include "share_dir.h"
#include "world.h"

static char dir[PATH_MAX];
static pthread_once_t found = PTHREAD_ONCE_INIT;

static void find(void)
{
    share_dir_find("scenes", "testpad.json", RCXSIM_SCENES, dir, sizeof dir);
}

const char *world_scenes_dir(void)
{
    pthread_once(&found, find);
    return dir;
}
