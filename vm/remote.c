/* SPDX-License-Identifier: MPL-2.0 */
/*
 * RemoteCommand (spec p. 61) and the transmit requests of SendPBMessage (p. 59) and SendUARTData (p. 60).
 *
 * The LEGO remote repeats its packet while a button is held, and the IR layer does not execute a packet whose
 * opcode byte repeats the previous one; so what arrives here is one packet per change of the buttons. Motor bits
 * are level-triggered (held while set), everything else acts on the press edge only: a one-shot button acts again
 * after a packet without it, normally `remote 0`.
 */
#include "rcx_string.h"
#include "rcx.h"
#include "hal.h"

RCX_STATIC_ASSERT(uartconf_is_hal_mode, HAL_IR_4800 == 1 && HAL_IR_76KHZ == 2 && HAL_IR_DUTY25 == 4);

/* n + the index of the lowest set bit of a non-zero byte. */
static u8 lowest_bit(u8 v, u8 n)
{
    while (!(v & 1u)) {
        v >>= 1;
        n++;
    }
    return n;
}

void remote_command(struct rcx *b, u16 bits)
{
    u16 pressed = (u16)(bits & ~b->remote.held);
    u16 changed = (u16)(bits ^ b->remote.held);

    b->remote.held = bits;
    /* Only a change of the motor buttons touches the motors: a one-shot button must not brake a program's motors. */
    if (changed & REMOTE_MOTORS)
        outputs_remote(b, (u8)(((u8)(bits >> 8) >> 3) & 7u),
                       (u8)(((u8)(bits >> 8) >> 6) | (((u8)bits & REMOTE_MOTOR_C_REV) << 2)));
    if (pressed & REMOTE_STOP) {
        sched_stop_all(b);
        outputs_program_stop(b);
    }
    if (pressed & REMOTE_PROGRAMS) {
        /* "prgm N, start 0" (spec p. 98): motors brake, the slot is selected and its task 0 started. */
        outputs_program_stop(b);
        sched_select_program(b, lowest_bit((u8)(pressed & REMOTE_PROGRAMS), (u8)-1), 1); /* bit 1: slot 0 */
    }
    if (pressed & REMOTE_SOUND)
        sound_system(b, REMOTE_SYSTEM_SOUND);
    if ((u8)(pressed >> 8) & (u8)(REMOTE_MESSAGES >> 8)) {
        /* As InternMessage would: PB message 1-3. */
        ops_set_message(b, lowest_bit((u8)(pressed >> 8), 1));
    }
}

void remote_send_message(struct rcx *b, u8 message)
{
    b->remote.tx[0] = RCX_OP_MESSAGE;
    b->remote.tx[1] = message;
    b->remote.tx_len = 2;
    b->remote.tx_pack = 0x07; /* a standard packet, as any host sends it */
    b->remote.tx_mode = 0; /* always as F7: receivers never take a message for a repeat (reference-firmware.md) */
    if (RCX_SWAN)
        b->remote.follow = 0;
}

void remote_send_uart(struct rcx *b, u8 start, u8 size)
{
    memcpy(b->remote.tx, b->uart + start, size); /* copied now: the program may rewrite the buffer before it goes out */
    b->remote.tx_len = size;
    b->remote.tx_pack = (u8)(b->uart[16] & 7u);
    b->remote.tx_mode = (u8)(b->uart[17] & 7u);
    if (RCX_SWAN)
        b->remote.follow = 0;
}

#if RCX_SWAN
void remote_send_message_param(struct rcx *b, u8 message, s16 param)
{
    b->remote.tx[0] = RCX_SW_MSG_WORD;
    b->remote.tx[1] = message;
    b->remote.tx[2] = (u8)param;
    b->remote.tx[3] = (u8)((u16)param >> 8);
    b->remote.tx_len = 4;
    b->remote.tx_pack = 0x07;
    b->remote.tx_mode = 0;
    b->remote.follow = (u8)(message + 1);
}

void remote_sent(struct rcx *b)
{
    u8 m = b->remote.follow;

    if (m)
        remote_send_message(b, (u8)(m - 1)); /* (which clears follow) */
}

void remote_param_received(struct rcx *b, const u8 *cmd)
{
    b->remote.rx_pmsg = (u8)(cmd[1] + 1);
    b->remote.rx_param = (s16)RCX_LE16(cmd + 2);
}

s16 remote_message_received(struct rcx *b, u8 message)
{
    u8 m = b->remote.rx_pmsg;

    b->remote.rx_pmsg = 0;
    return m == (u8)(message + 1) ? b->remote.rx_param : 0; /* a plain message: parameter 0 */
}
#endif
