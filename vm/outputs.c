/* Motor registers and status sources. Applying them to hal_motor() is owed to the outputs engine. */
#include "rcx.h"

void outputs_init(struct rcx *b)
{
    u8 i;
    for (i = 0; i < RCX_MOTORS; i++) {
        b->out.motor[i] = RCX_MOTOR_FWD | 7;
        b->out.global[i] = RCX_MOTOR_ON | RCX_MOTOR_FWD | 7;
    }
}

void outputs_changed(struct rcx *b) { b->engine_pending++; }
void outputs_tick(struct rcx *b) { (void)b; }

/* Motor status as firm0328 reports it: the effective output after global invert, max power and disconnect. */
u8 outputs_status(const struct rcx *b, u8 i)
{
    u8 m = b->out.motor[i], g = b->out.global[i];
    u8 power = (u8)(m & RCX_MOTOR_POWER);
    u8 status;

    if (power > (g & RCX_MOTOR_POWER))
        power = (u8)(g & RCX_MOTOR_POWER);
    status = (u8)((m & (RCX_MOTOR_ON | RCX_MOTOR_BRAKE)) | power);
    if ((m ^ g ^ RCX_MOTOR_FWD) & RCX_MOTOR_FWD) /* forward xor globally reversed */
        status |= RCX_MOTOR_FWD;
    if (!(g & RCX_MOTOR_ON) && (m & RCX_MOTOR_ON))
        status = (u8)((status & ~RCX_MOTOR_ON) | RCX_MOTOR_BRAKE);
    return status;
}

/* firm0328 always sets bits 4-5 here (reference-firmware.md); bit 6 is not part of this layout. */
u8 outputs_global_status(const struct rcx *b, u8 i)
{
    return (u8)((b->out.global[i] & 0x8F) | 0x30);
}

void outputs_program_start(struct rcx *b) { b->engine_pending++; }
void outputs_program_stop(struct rcx *b) { b->engine_pending++; }
void outputs_remote(struct rcx *b, u8 fwd_mask, u8 rev_mask) { (void)fwd_mask; (void)rev_mask; b->engine_pending++; }
void outputs_revoked(struct rcx *b, u8 resources) { (void)resources; b->engine_pending++; }
