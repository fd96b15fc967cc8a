/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The TCP IR link of NQC 4 (-Stcp), brickOS-bibo and brickEmu's ir-server: a raw byte stream both ways, no framing,
 * port 50637 by default. Three ways into the IR room:
 *   --tcp [ADDR:]PORT        rcxsim is the hub: every client is a port of the room (net.c);
 *   --tcp-tower [ADDR:]PORT  a brick's own tower: the same, but its clients face that brick alone (net.c);
 *   --tcp-join HOST:PORT     the room joins a hub (ir-server, or another rcxsim --tcp) as one of its clients, and
 *                            joins it again when it comes back (net_join.c).
 */
#ifndef RCX_NET_H
#define RCX_NET_H

#include <stddef.h>
#include "room.h"

#define NET_DEFAULT_PORT "50637"

/* 0, or -1 with a one-line reason in err (without the option's name). net_hub_open prints "rcxsim: <what> at
 * ADDR:PORT (tcp)"; `facing` NULL is the hub, else the brick port its clients face. */
int net_hub_open(struct room *r, const char *spec, struct room_port *facing, const char *what, char *err,
                 size_t errlen);
int net_join(struct room *r, const char *spec, char *err, size_t errlen);

/* Shared by both files: "[ADDR:]PORT", "HOST[:PORT]" or "[IPV6]:PORT" into host and port (0, or -1: malformed). */
int net_split(const char *spec, const char *host_default, char *host, size_t hostlen, char *port, size_t portlen);
void net_nonblocking(int fd);

#endif
