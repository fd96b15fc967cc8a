/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Motor registers, the effective output of each motor, and the reversing pause.
 *
 * The registers are what programs set and read (source 3, 17); the effective output is what the hardware gets:
 * direction after the global invert, power capped by the global maximum, and a globally disconnected motor held
 * in the global register's own off (brake) or float state whatever its own register says.
 */
#include "rcx.h"
#include "hal.h"

#define ALL_MOTORS 0x07
#define SET(value) OUTPUTS_CHANGE(0xFF, value)
#define STOP OUTPUTS_CHANGE(RCX_MOTOR_ON | RCX_MOTOR_BRAKE, RCX_MOTOR_BRAKE) /* off, braked, the rest kept */

/* firm0328 reads 0x4F (off = brake, forward, power 7) for every output right after it has started and after it
 * was switched off (reference-firmware.md), which is also the state of spec p. 98 for starting a program; the
 * port's latch floats until then. */
void outputs_init(struct rcx *b)
{
    outputs_update(b, OUTPUTS_GLOBAL | ALL_MOTORS, SET(RCX_MOTOR_ON | RCX_MOTOR_FWD | 7));
    outputs_program_start(b);
}

/* Motor status as firm0328 reports it: the effective output after global invert, max power and disconnect. */
u8 outputs_status(const struct rcx *b, u8 i)
{
    u8 m = b->out.motor[i], g = b->out.global[i], power = (u8)(m & RCX_MOTOR_POWER), max = (u8)(g & RCX_MOTOR_POWER);
    u8 status;

    if (power > max)
        power = max;
    status = (u8)((m & (RCX_MOTOR_ON | RCX_MOTOR_BRAKE)) | power);
    if (!((m ^ g) & RCX_MOTOR_FWD)) /* forward xor globally reversed */
        status |= RCX_MOTOR_FWD;
    if (m & ~g & RCX_MOTOR_ON) /* on, but globally disconnected */
        status = (u8)((status & ~RCX_MOTOR_ON) | RCX_MOTOR_BRAKE);
    return status;
}

/*
 * What the hardware gets: the motor's status (source 3) drives it, except that a globally disconnected motor is held
 * in the global register's off (brake) or float state. Kept (rcx_outputs.applied) as a status byte with nothing but
 * RCX_MOTOR_BRAKE left when it is off, so that equal states are equal bytes (a register that is on has no brake bit:
 * switching on drops it, vm/ops.c).
 *
 * The six states of spec p. 99 are the on/off/float and direction bits of the register; the rule that goes with
 * them is the pause: going straight from driving one way to driving the other, the motor is braked for 60 ms first.
 * Requests during the pause take effect at its end, except that stopping (brake or float) ends it at once.
 */
static void apply(struct rcx *b, u8 i)
{
    u8 want = outputs_status(b, i), g = b->out.global[i], *now = &b->out.applied[i], *pause = &b->out.pause[i];

    if (!(g & RCX_MOTOR_ON))
        want = g;
    if (!(want & RCX_MOTOR_ON)) { /* stopped (braked or floating): a pause ends at once */
        want &= RCX_MOTOR_BRAKE;
        *pause = 0;
    } else if (*pause) {
        return;
    } else if (*now & RCX_MOTOR_ON && (want ^ *now) & RCX_MOTOR_FWD) { /* driven one way, now the other */
        *pause = OUTPUTS_REVERSE_PAUSE_MS;
        want = RCX_MOTOR_BRAKE;
    }
    if (want != *now) {
        *now = want;
        /* Brake holds at full strength: a stopped motor should not give way under load. */
        if (want & RCX_MOTOR_ON)
            hal_motor(b, i, (u8)(HAL_MOTOR_REV + (want >> 3 & 1)), (u8)(want & RCX_MOTOR_POWER));
        else if (want)
            hal_motor(b, i, HAL_MOTOR_BRAKE, 7);
        else
            hal_motor(b, i, HAL_MOTOR_FLOAT, 0);
    }
}

void outputs_changed(struct rcx *b)
{
    u8 i;
    for (i = 0; i < RCX_MOTORS; i++)
        apply(b, i);
}

/* A pause that ends lets its motor be driven as its registers say; the others stay as they are (apply() changes
 * nothing where nothing changed). */
void outputs_tick(struct rcx *b)
{
    u8 n = RCX_MOTORS, *pause = b->out.pause;

    do
        if (*pause)
            --*pause;
    while (pause++, --n);
    outputs_changed(b);
}

void outputs_update(struct rcx *b, u8 list, u16 change)
{
    u8 *reg = b->out.motor;

    if (list & OUTPUTS_GLOBAL)
        reg = b->out.global;
    /* The bytes of `change` used where they are: copied into variables of their own, one spills to the stack. */
    for (list &= ALL_MOTORS; list; list >>= 1, reg++)
        if (list & 1)
            *reg = (u8)((*reg & ~(change >> 8)) ^ change);
    outputs_changed(b);
}


void outputs_program_start(struct rcx *b)
{
    outputs_update(b, ALL_MOTORS, SET(RCX_MOTOR_FWD | RCX_MOTOR_BRAKE | 7));
}

void outputs_program_stop(struct rcx *b)
{
    outputs_update(b, ALL_MOTORS, STOP);
}

/*
 * Spec p. 98 says held buttons make their motors "FORWARD, ON and MAX power"; a motor's reverse button can only
 * mean reverse, so each motor runs the way its button points (forward wins if both are held). Releasing every
 * button leaves all motors forward, braked, at full power.
 */
void outputs_remote(struct rcx *b, u8 fwd_mask, u8 rev_mask)
{
    if (!((fwd_mask | rev_mask) & ALL_MOTORS)) {
        outputs_program_start(b);
        return;
    }
    outputs_update(b, (u8)(rev_mask & ~fwd_mask & ALL_MOTORS), SET(RCX_MOTOR_ON | 7));
    outputs_update(b, (u8)(fwd_mask & ALL_MOTORS), SET(RCX_MOTOR_ON | RCX_MOTOR_FWD | 7));
}

/* Resource bits of spec p. 106: 0x01 A, 0x02 B, 0x08 C (0x04 is the sound). */
void outputs_revoked(struct rcx *b, u8 resources)
{
    outputs_update(b, (u8)((resources & 0x03) | ((resources >> 1) & 0x04)), STOP);
}
