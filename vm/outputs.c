/*
 * Motor registers, the effective output of each motor, and the reversing pause.
 *
 * The registers are what programs set and read (source 3, 17); the effective output is what the hardware gets:
 * direction after the global invert, power capped by the global maximum, and a globally disconnected motor held
 * in the global register's own off (brake) or float state whatever its own register says.
 */
#include "rcx.h"
#include "hal.h"

#define APPLIED(mode, level) ((u8)((level) << 2 | (mode)))
/* Driven forward or backward (not braked, not floating): of the modes 0-3 only REV (1) and FWD (2) have bit 1 set in
 * mode + 1 (a carry out of the mode bits leaves it clear). */
#define DRIVEN(applied) ((u8)((applied) + 1) & 2)
RCX_STATIC_ASSERT(driven_modes, HAL_MOTOR_FLOAT == 0 && HAL_MOTOR_REV == 1 && HAL_MOTOR_FWD == 2 &&
                                HAL_MOTOR_BRAKE == 3);

void outputs_init(struct rcx *b)
{
    u8 i;
    for (i = 0; i < RCX_MOTORS; i++) {
        b->out.motor[i] = RCX_MOTOR_FWD | 7;
        b->out.global[i] = RCX_MOTOR_ON | RCX_MOTOR_FWD | 7;
    }
    /* applied[] stays 0 (float, level 0): what the port's motor latch holds at start-up. */
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
 * in the global register's off (brake) or float state. Brake holds at full strength: a stopped motor should not give
 * way under load.
 */
static u8 wanted(const struct rcx *b, u8 i)
{
    u8 st = outputs_status(b, i), g = b->out.global[i];

    if (!(g & RCX_MOTOR_ON))
        st = g;
    if (st & RCX_MOTOR_ON)
        return (u8)((u8)(st << 2 & 0x1C) + HAL_MOTOR_REV + (st >> 3 & 1)); /* power << 2; FWD (bit 3) is REV + 1 */
    return (st & RCX_MOTOR_BRAKE) ? APPLIED(HAL_MOTOR_BRAKE, 7) : APPLIED(HAL_MOTOR_FLOAT, 0);
}

/*
 * The six states of spec p. 99 are the on/off/float and direction bits of the register; the rule that goes with
 * them is the pause: going straight from driving one way to driving the other, the motor is braked for 60 ms first.
 * Requests during the pause take effect at its end, except that stopping (brake or float) ends it at once.
 */
static void apply(struct rcx *b, u8 i)
{
    u8 want = wanted(b, i), now = b->out.applied[i], *pause = &b->out.pause[i];

    if (*pause) {
        if (DRIVEN(want))
            return;
        *pause = 0;
    } else if (!((u8)~(now ^ want) & 3) && DRIVEN(now)) { /* driven one way, now wanted the other */
        *pause = OUTPUTS_REVERSE_PAUSE_MS;
        want = APPLIED(HAL_MOTOR_BRAKE, 7);
    }
    if (want != now) {
        b->out.applied[i] = want;
        hal_motor(b, i, (u8)(want & 3), (u8)(want >> 2));
    }
}

void outputs_changed(struct rcx *b)
{
    u8 i;
    for (i = 0; i < RCX_MOTORS; i++)
        apply(b, i);
}

void outputs_tick(struct rcx *b)
{
    u8 i;
    for (i = 0; i < RCX_MOTORS; i++)
        if (b->out.pause[i] && !--b->out.pause[i])
            apply(b, i);
}

/* firm0328 always sets bits 4-5 here (reference-firmware.md); bit 6 is not part of this layout. */
u8 outputs_global_status(const struct rcx *b, u8 i)
{
    return (u8)((b->out.global[i] & 0x8F) | 0x30);
}

#define ALL_MOTORS 0x07
#define STOP 0 /* for rewrite(): off, braked, the rest of the register kept */

/* Set the registers of the motors in `list` (bit 0 A, 1 B, 2 C) to `value`, or stop them (STOP). */
static void rewrite(struct rcx *b, u8 list, u8 value)
{
    u8 *m;
    for (m = b->out.motor, list &= ALL_MOTORS; list; list >>= 1, m++)
        if (list & 1)
            *m = value != STOP ? value : (u8)((*m & ~RCX_MOTOR_ON) | RCX_MOTOR_BRAKE);
    outputs_changed(b);
}

void outputs_program_start(struct rcx *b)
{
    rewrite(b, ALL_MOTORS, RCX_MOTOR_FWD | RCX_MOTOR_BRAKE | 7);
}

void outputs_program_stop(struct rcx *b)
{
    rewrite(b, ALL_MOTORS, STOP);
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
    rewrite(b, (u8)(rev_mask & ~fwd_mask), RCX_MOTOR_ON | 7);
    rewrite(b, fwd_mask, RCX_MOTOR_ON | RCX_MOTOR_FWD | 7);
}

/* Resource bits of spec p. 106: 0x01 A, 0x02 B, 0x08 C (0x04 is the sound). */
void outputs_revoked(struct rcx *b, u8 resources)
{
    rewrite(b, (u8)((resources & 0x03) | ((resources >> 1) & 0x04)), STOP);
}
