/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Where rcxsim's installed data lives: `../share/openrcx/<sub>` next to the executable (bin/rcxsim, as `make
 * install` and the Debian package lay it out, under whatever prefix), else a folder of the source tree it was built
 * from. Shared by the panel's page (panel_files.c) and the world's scenes (world/world_files.c).
 */
#ifndef RCX_SHARE_DIR_H
#define RCX_SHARE_DIR_H

#include <stddef.h>

/* Into dir: the installed folder `sub` if its file `probe` is readable there (its real path), else `source`. */
void share_dir_find(const char *sub, const char *probe, const char *source, char *dir, size_t size);

#endif
