/*
 * The TCP IR link of NQC 4 (-Stcp), brickOS-bibo and brickEmu's ir-server (net.c): a raw byte stream both ways,
 * no framing, port 50637 by default. Two ways into the IR room:
 *   --tcp [ADDR:]PORT   rcxsim is the hub: every client is a port of the room;
 *   --tcp-join HOST:PORT the room joins a hub (ir-server, or another rcxsim --tcp) as one of its clients.
 */
#ifndef RCX_NET_H
#define RCX_NET_H

#include <stddef.h>
#include "room.h"

#define NET_DEFAULT_PORT "50637"

/* 0, or -1 with a one-line reason in err (without the option's name). */
int net_hub_open(struct room *r, const char *spec, char *err, size_t errlen);
int net_join(struct room *r, const char *spec, char *err, size_t errlen);

#endif
