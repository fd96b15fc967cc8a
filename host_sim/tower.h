/* SPDX-License-Identifier: MPL-2.0 */
/* A serial IR tower on a pseudo-terminal (--tty), a way into the IR room (tower.c). */
#ifndef RCX_TOWER_H
#define RCX_TOWER_H

#include "room.h"

/* Opens a pseudo-terminal, links `path` to it and puts its tower in the room, facing `brick`. -1 with errno. */
int tower_open(struct room *r, const char *path, struct room_port *brick);

#endif
