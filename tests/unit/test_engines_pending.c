/*
 * Byte codes whose full effect needs the engines of the next issue (outputs to hal.h, sound, display, events,
 * monitoring, access control, IR transmission) are decoded and dispatched, and each call is counted in
 * rcx.engine_pending instead of being silently accepted. When an engine is written, its rows move out of this
 * table into a test that asserts the real effect.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include "brick.h"

struct owed {
    const char *what;
    u8 bytes[8];
    u8 len;
};

/* Direct commands (each with in-range operands, so it reaches its engine). */
static const struct owed direct_rows[] = {
    { "ClearSound", { 0x80 }, 1 },
    { "ClearPBMessage (mailbox event)", { 0x90 }, 1 },
    { "MuteSound", { 0xD0 }, 1 },
    { "ClearAllEvents", { 0x06 }, 1 },
    { "OnOffFloat", { 0x21, 0x81 }, 2 },
    { "PlaySystemSound", { 0x51, 0x02 }, 2 },
    { "ClearSensorValue", { 0xD1, 0x00 }, 2 },
    { "SetFwdSetRwdRewDir", { 0xE1, 0x81 }, 2 },
    { "ConnectDisconnect", { 0x67, 0x81 }, 2 },
    { "SetNormSetInvAltDir", { 0x77, 0x81 }, 2 },
    { "IncCounter (counter event)", { 0x97, 0x00 }, 2 },
    { "DecCounter (counter event)", { 0xA7, 0x01 }, 2 },
    { "ClearCounter (counter event)", { 0xB7, 0x02 }, 2 },
    { "InternMessage (mailbox event)", { 0xF7, 0x05 }, 2 },
    { "PlayToneVar", { 0x02, 0x00, 0x0A }, 3 },
    { "SetWatch (watch view)", { 0x22, 0x01, 0x02 }, 3 },
    { "SetSensorType", { 0x32, 0x00, 0x01 }, 3 },
    { "SetSensorMode", { 0x42, 0x00, 0x20 }, 3 },
    { "SendUARTData", { 0xC2, 0x00, 0x04 }, 3 },
    { "RemoteCommand", { 0xD2, 0x00, 0x08 }, 3 },
    { "DirectEvent", { 0x03, 0x02, 0x01, 0x00 }, 4 },
    { "SetPower", { 0x13, 0x01, 0x02, 0x03 }, 4 },
    { "PlayTone", { 0x23, 0xB8, 0x01, 0x0A }, 4 },
    { "SelectDisplay", { 0x33, 0x02, 0x01, 0x00 }, 4 },
    { "SetEvent", { 0x93, 0x01, 0x00, 0x00 }, 4 },
    { "SetMaxPower", { 0xA3, 0x01, 0x02, 0x03 }, 4 },
    { "CalibrateEvent", { 0x04, 0x01, 0x0A, 0x14, 0x1E }, 5 },
    { "ViewSourceValue", { 0xE5, 0x00, 0x02, 0x00, 0x00, 0x00 }, 6 },
};

static void direct_commands_reach_their_engine(void **state)
{
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof direct_rows / sizeof direct_rows[0]; i++) {
        struct rcx *b = brick_new();
        u16 before = b->engine_pending;
        brick_cmd(b, direct_rows[i].bytes, direct_rows[i].len, NULL);
        if (b->engine_pending == before)
            fail_msg("%s did not reach its engine", direct_rows[i].what);
        brick_free(b);
    }
}

/* Program-only byte codes: monitoring, access control, SendPBMessage, and the EndOfSub/stop notifications. */
static void program_codes_reach_their_engine(void **state)
{
    static const struct owed rows[] = {
        { "SEnterEventCheck", { 0xB4, 0x02, 0x01, 0x00, 0x00 }, 5 },
        { "LEnterEventCheck", { 0xB5, 0x02, 0x01, 0x00, 0x00, 0x00 }, 6 },
        { "ExitEventCheck", { 0xB0 }, 1 },
        { "EnterAccessControl", { 0x73, 0x01, 0x00, 0x00 }, 4 },
        { "ExitAccessControl", { 0xA0 }, 1 },
        { "SendPBMessage", { 0xB2, 0x02, 0x07 }, 3 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        u16 before;
        assert_int_equal(brick_download(b, 1, 0, rows[i].bytes, rows[i].len), 0);
        before = b->engine_pending;
        brick_start(b, 0);
        brick_run_ms(b, 1, 1);
        if (b->engine_pending == before)
            fail_msg("%s did not reach its engine", rows[i].what);
        brick_free(b);
    }
}

/* Out-of-range operands are rejected before any engine sees them (spec: event numbers 0-15, sounds 0-5 ...). */
static void bad_operands_stop_before_the_engine(void **state)
{
    static const struct owed rows[] = {
        { "PlaySystemSound 6", { 0x51, 0x06 }, 2 },
        { "ClearSensorValue 3", { 0xD1, 0x03 }, 2 },
        { "IncCounter 3", { 0x97, 0x03 }, 2 },
        { "SetSensorType sensor 3", { 0x32, 0x03, 0x01 }, 3 },
        { "SetSensorType type 5", { 0x32, 0x00, 0x05 }, 3 },
        { "SetSensorMode sensor 3", { 0x42, 0x03, 0x20 }, 3 },
        { "SetWatch 24:00", { 0x22, 0x18, 0x00 }, 3 },
        { "SetWatch 0:60", { 0x22, 0x00, 0x3C }, 3 },
        { "SendUARTData past the buffer", { 0xC2, 0x0C, 0x05 }, 3 },
        { "SetPower 8", { 0x13, 0x01, 0x02, 0x08 }, 4 },
        { "SelectDisplay 8", { 0x33, 0x02, 0x08, 0x00 }, 4 },
        { "SetEvent event 16", { 0x93, 0x10, 0x00, 0x00 }, 4 },
        { "SetEvent sensor 11", { 0x93, 0x01, 0x0B, 0x00 }, 4 },
        { "SetEvent type 13", { 0x93, 0x01, 0x00, 0x0D }, 4 },
        { "CalibrateEvent 16", { 0x04, 0x10, 0x0A, 0x14, 0x1E }, 5 },
        { "ViewSourceValue precision 4", { 0xE5, 0x00, 0x04, 0x00, 0x00, 0x00 }, 6 },
    };
    unsigned i;
    (void)state;
    for (i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        struct rcx *b = brick_new();
        u16 before = b->engine_pending;
        brick_cmd(b, rows[i].bytes, rows[i].len, NULL);
        if (b->engine_pending != before)
            fail_msg("%s reached an engine", rows[i].what);
        brick_free(b);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(direct_commands_reach_their_engine),
        cmocka_unit_test(program_codes_reach_their_engine),
        cmocka_unit_test(bad_operands_stop_before_the_engine),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
