/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The machine's side of the IR link: RemoteCommand (spec p. 61), and what programs ask to transmit
 * (SendPBMessage p. 59, SendUARTData p. 60). The runtime's IR layer picks up the request and sends it when the link
 * is free; one request waits at a time, and a newer one replaces it.
 */
#ifndef RCX_REMOTE_H
#define RCX_REMOTE_H

#include "rcx_types.h"

struct rcx;

/* RemoteCommand bits (spec p. 61): low byte first on the wire, so bit 8 is the high byte's 0x01. */
#define REMOTE_MOTOR_C_REV 0x0001u
#define REMOTE_PROGRAM_1 0x0002u   /* ... 0x0020 program 5 */
#define REMOTE_PROGRAMS 0x003Eu
#define REMOTE_STOP 0x0040u
#define REMOTE_SOUND 0x0080u
#define REMOTE_MESSAGE_1 0x0100u   /* 0x0200 message 2, 0x0400 message 3 */
#define REMOTE_MESSAGES 0x0700u
#define REMOTE_MOTOR_A_FWD 0x0800u /* 0x1000 B, 0x2000 C */
#define REMOTE_MOTOR_A_REV 0x4000u /* 0x8000 B; C backwards is bit 0 */
#define REMOTE_MOTORS 0xF801u

#define REMOTE_SYSTEM_SOUND 1      /* the remote's sound button: beep-beep */
#define REMOTE_TX_MAX 16           /* source 33 data bytes */

struct rcx_remote {
    u16 held;       /* bits of the last RemoteCommand: one-shot buttons act only when newly pressed */
    u8 tx_len;      /* bytes of the waiting transmit request, 0 = none */
    u8 tx_pack;     /* framing: IR_PACK_* bits (src/ir.h), PackConf of source 33 */
    u8 tx_mode;     /* line: HAL_IR_* bits, UartConf of source 33 */
    u8 tx[REMOTE_TX_MAX];
    u8 follow;      /* a message (F7) to send once the request in tx has gone: 1 + the message, 0 none */
    u8 rx_pmsg;     /* a parameter received ahead of its message (B3 m lo hi): 1 + m, 0 none */
    s16 rx_param;
};

void remote_command(struct rcx *b, u16 bits);               /* 0xD2 */
void remote_send_message(struct rcx *b, u8 message);         /* 0xB2 */
void remote_send_uart(struct rcx *b, u8 start, u8 size);     /* 0xC2, start + size <= 16 checked */
/* Swan's message with a parameter (0xC3). On the wire: `B3 m lo hi` (a standard packet that firm0328 ignores: no
 * such direct command), then `F7 m` once it is out and the room quiet again; a receiving OpenRCX keeps the parameter
 * and gives it to the message that follows, a firm0328 brick takes the plain message. */
void remote_send_message_param(struct rcx *b, u8 message, s16 param);
void remote_sent(struct rcx *b);     /* the IR layer sent tx and the room is quiet: the follow-up message into tx */
void remote_param_received(struct rcx *b, const u8 *cmd);         /* direct B3 m lo hi */
s16 remote_message_received(struct rcx *b, u8 message);           /* direct F7 m: the parameter it brings */

#endif
