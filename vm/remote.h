/*
 * The machine's side of the IR link: RemoteCommand (spec p. 61), and what programs ask to transmit
 * (SendPBMessage p. 59, SendUARTData p. 60). The runtime's IR layer picks up the requests and sends them.
 */
#ifndef RCX_REMOTE_H
#define RCX_REMOTE_H

#include "rcx_types.h"

struct rcx;

struct rcx_remote {
    u8 tx_pending;  /* placeholder until the IR issue defines the transmit requests */
};

void remote_command(struct rcx *b, u16 bits);               /* 0xD2 */
void remote_send_message(struct rcx *b, u8 message);         /* 0xB2 */
void remote_send_uart(struct rcx *b, u8 start, u8 size);     /* 0xC2, start + size <= 16 checked */

#endif
