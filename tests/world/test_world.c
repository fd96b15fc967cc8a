/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The world library on its own (host_sim/world/world.h), without a brick: the A/D values its sensors give for
 * known places and motions, placing, the JSON the panel reads, replacing the floor, reproducibility. Expected raw
 * values are docs/world.md's: white paper 711, black line 817 (50 % and 33 % through the firmware's percent
 * formula), touch released 1023 / pressed 50, rotation levels 1023, 777, 368, 532 counting up.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "world.h"

#define FWD7 (2u << 3 | 7u)        /* enum hal_motor_mode fwd, power 7 */

static struct world *load(const char *name)
{
    char path[4096], err[512];
    struct world *w;
    snprintf(path, sizeof path, "%s/%s", world_scenes_dir(), name);
    w = world_load(path, err, sizeof err);
    if (!w)
        fail_msg("%s", err);
    return w;
}

static void steps(struct world *w, struct world_brick_io *io, int nbricks, int ms)
{
    while (ms-- > 0)
        world_step(w, io, nbricks);
}

static void light_reads_white_paper_and_black_line(void **state)
{
    struct world *w = load("testpad.json");
    struct world_brick_io io = { .sensor_power = { 0, 1, 0 } };
    (void)state;
    /* The sensor is 60 mm ahead of the centre: at (560, 200) it is on the middle of the bottom straight. */
    assert_int_equal(world_place(w, 1, 0, 500, 200, 0), 0);
    steps(w, &io, 1, 1);
    assert_int_equal(io.raw[1], 817);
    assert_int_equal(world_place(w, 1, 0, 500, 400, 0), 0);
    steps(w, &io, 1, 1);
    assert_int_equal(io.raw[1], 711);
    io.sensor_power[1] = 0;        /* unpowered, it gives nothing: the pull-up */
    steps(w, &io, 1, 1);
    assert_int_equal(io.raw[1], 1023);
    world_free(w);
}

static void bumpers_press_on_a_wall_only(void **state)
{
    struct world *w = load("arena.json");
    struct world_brick_io io = { 0 };
    (void)state;
    steps(w, &io, 1, 5);
    assert_int_equal(io.raw[0], 1023);
    assert_int_equal(io.raw[2], 1023);
    /* Facing west 102 mm from the west wall's middle: the chassis' front is at 22 mm, its bumpers reach 8 mm, into
     * the wall (inner face at 20 mm). Chipmunk pushes them apart and they stay touching. */
    assert_int_equal(world_place(w, 1, 0, 102, 600, 180), 0);
    steps(w, &io, 1, 5);
    assert_int_equal(io.raw[0], 50);
    assert_int_equal(io.raw[2], 50);
    world_free(w);
}

/* The firmware's phases of the rotation levels (vm/sensors.c): 1023 -> 0, 777 -> 1, 368 -> 2, 532 -> 3. */
static int phase(unsigned raw)
{
    return raw >= 960 ? 0 : raw >= 768 ? 1 : raw >= 512 ? 3 : raw >= 320 ? 2 : -1;
}

static void rotation_counts_sixteen_a_turn_forwards(void **state)
{
    char path[4096], err[512], pose[256];
    struct world *w;
    struct world_brick_io io = { .motor = { FWD7, 0, FWD7 } };
    int count = 0, last, ms;
    double x, y, h;
    (void)state;
    snprintf(path, sizeof path, "%s/odometry.json", TESTS_WORLD_DIR);
    w = world_load(path, err, sizeof err);
    assert_non_null(w);
    steps(w, &io, 1, 1);
    last = phase(io.raw[0]);
    assert_int_equal(last, 0);
    for (ms = 0; ms < 5000; ms++) { /* 5 s at 271 mm/s: 10 turns */
        int p;
        world_step(w, &io, 1);
        p = phase(io.raw[0]);
        assert_true(p >= 0);
        assert_true(((p - last) & 3) <= 1); /* never backwards, never a jump of two */
        count += (p - last) & 3;
        last = p;
    }
    assert_true(world_robot_pose(w, 0, pose, sizeof pose) > 0);
    assert_int_equal(sscanf(pose, "\"robot\":0,\"x\":%lf,\"y\":%lf,\"h\":%lf", &x, &y, &h), 3);
    /* Driving north from (1000, 300): the wheel rolls without slipping once under way, 16 counts per pi * 43.2 mm. */
    assert_true(abs(count - (int)((y - 300) / (3.14159265 * 43.2) * 16)) <= 1);
    assert_true(count > 150);
    world_free(w);
}

/* The odometry scene's light sensor (input 2) on white paper with noise 4, seed 7: within 4 of 711, not always the
 * same, and the same sequence in two worlds. */
static void light_noise_is_seeded(void **state)
{
    char path[4096], err[512];
    struct world *a, *b;
    struct world_brick_io ia = { .sensor_power = { 0, 1, 0 } }, ib = ia;
    unsigned lo = 1023, hi = 0;
    int ms;
    (void)state;
    snprintf(path, sizeof path, "%s/odometry.json", TESTS_WORLD_DIR);
    a = world_load(path, err, sizeof err);
    b = world_load(path, err, sizeof err);
    assert_non_null(a);
    assert_non_null(b);
    for (ms = 0; ms < 200; ms++) {
        world_step(a, &ia, 1);
        world_step(b, &ib, 1);
        assert_int_equal(ia.raw[1], ib.raw[1]);
        lo = ia.raw[1] < lo ? ia.raw[1] : lo;
        hi = ia.raw[1] > hi ? ia.raw[1] : hi;
    }
    assert_true(lo >= 707 && hi <= 715 && lo < hi);
    world_free(a);
    world_free(b);
}

static double robot_y(const struct world *w)
{
    char pose[256];
    double x, y, h;
    assert_true(world_robot_pose(w, 0, pose, sizeof pose) > 0);
    assert_int_equal(sscanf(pose, "\"robot\":0,\"x\":%lf,\"y\":%lf,\"h\":%lf", &x, &y, &h), 3);
    return y;
}

/* From full speed northwards (271 mm/s): floating, the robot rolls on against the rolling resistance alone (0.03 g:
 * v^2 / 2a = 125 mm); braked, the shorted motors stop it within the tyres' grip (0.64 g: 6 mm). */
static void float_coasts_and_brake_stops(void **state)
{
    char path[4096], err[512];
    struct world *w;
    struct world_brick_io io = { .motor = { FWD7, 0, FWD7 } };
    int mode;
    (void)state;
    snprintf(path, sizeof path, "%s/odometry.json", TESTS_WORLD_DIR);
    for (mode = 0; mode <= 3; mode += 3) {
        double y0, y1;
        w = world_load(path, err, sizeof err);
        assert_non_null(w);
        assert_int_equal(world_place(w, 1, 0, 1000, 20, 90), 0);
        io.motor[0] = io.motor[2] = FWD7;
        steps(w, &io, 1, 1000);
        y0 = robot_y(w);
        io.motor[0] = io.motor[2] = (unsigned char)(mode << 3 | 7);
        steps(w, &io, 1, 2000);
        y1 = robot_y(w);
        if (mode == 0)
            assert_true(y1 - y0 > 100 && y1 - y0 < 150);
        else
            assert_true(y1 - y0 > 2 && y1 - y0 < 10);
        world_free(w);
    }
}

/* A robot pushes a movable obstacle, even one that has been still long enough to sleep, and a fixed one stops both:
 * the arena's 80 mm yellow box at (700, 400), the robot 150 mm west of it facing it, both left alone for 2 s, then
 * driven for 2 s. */
static void robot_pushes_a_sleeping_obstacle(void **state)
{
    struct world *w = load("arena.json");
    struct world_brick_io io = { 0 };
    char json[4096];
    const char *box;
    double x;
    (void)state;
    assert_int_equal(world_place(w, 1, 0, 550, 400, 0), 0);
    steps(w, &io, 1, 2000);
    io.motor[0] = io.motor[2] = FWD7;
    steps(w, &io, 1, 2000);
    world_pose_json(w, json, sizeof json);
    box = strstr(json, "{\"i\":3,\"x\":");
    assert_non_null(box);
    assert_int_equal(sscanf(box, "{\"i\":3,\"x\":%lf", &x), 1);
    /* Pushed east at about 263 mm/s until it meets the fixed box whose west face is at x 1020: its centre at 980. */
    assert_true(x > 975 && x < 985);
    world_free(w);
}

static void placing_checks_the_floor_and_the_index(void **state)
{
    struct world *w = load("arena.json");
    char json[4096];
    (void)state;
    assert_int_equal(world_place(w, 1, 0, 1600, 100, 0), -1);
    assert_int_equal(world_place(w, 1, 0, 100, -1, 0), -1);
    assert_int_equal(world_place(w, 1, 1, 100, 100, 0), -1);
    assert_int_equal(world_place(w, 0, 4, 100, 100, 0), -1);
    assert_int_equal(world_place(w, 0, 3, 750, 600, 45), 0);
    assert_int_equal(world_place(w, 1, 0, 300, 900, 270), 0);
    assert_true(world_pose_json(w, json, sizeof json) > 0);
    assert_non_null(strstr(json, "\"robots\":[{\"i\":0,\"x\":300.0,\"y\":900.0,\"h\":270.0,\"inputs\":["));
    assert_non_null(strstr(json, "{\"i\":3,\"x\":750.0,\"y\":600.0,\"h\":45.0}"));
    world_free(w);
}

static void scene_json_has_the_panel_shapes(void **state)
{
    struct world *w = load("arena.json");
    char json[8192];
    size_t n;
    (void)state;
    n = world_scene_json(w, json, sizeof json);
    assert_true(n > 0 && n == strlen(json));
    assert_non_null(strstr(json, "{\"scene\":\"arena\",\"floor\":{\"w\":1500,\"h\":1200,\"version\":1},\"walls\":[{"));
    assert_non_null(strstr(json, "{\"i\":2,\"shape\":\"circle\",\"r\":60,\"color\":\"#27ae60\",\"movable\":true}"));
    assert_non_null(strstr(json, "\"robots\":[{\"i\":0,\"brick\":0,\"name\":\"bumper car\",\"w\":120,\"l\":160,"));
    assert_non_null(strstr(json, "{\"input\":2,\"kind\":\"light\",\"x\":60,\"y\":0}"));
    assert_int_equal(world_scene_json(w, json, n), 0); /* no room for the NUL: does not fit */
    world_free(w);
}

static void floor_picture_replaced_or_refused(void **state)
{
    struct world *w = load("testpad.json"), *paper = load("arena.json");
    const unsigned char *png, *white;
    size_t len, wlen;
    unsigned char *copy;
    char err[256], json[4096];
    struct world_brick_io io = { .sensor_power = { 0, 1, 0 } };
    (void)state;
    assert_int_equal(world_floor_png(w, &png, &len), 0);
    assert_true(len > 8 && memcmp(png, "\x89PNG", 4) == 0);
    assert_int_equal(world_set_floor_png(w, (const unsigned char *)"not a png", 9, err, sizeof err), -1);
    assert_true(strlen(err) > 0);
    assert_int_equal(world_floor_png(paper, &white, &wlen), 0);
    copy = malloc(wlen);
    memcpy(copy, white, wlen);
    assert_int_equal(world_set_floor_png(w, copy, wlen, err, sizeof err), 0);
    free(copy);
    world_scene_json(w, json, sizeof json);
    assert_non_null(strstr(json, "\"floor\":{\"w\":1400,\"h\":1000,\"version\":2}"));
    assert_int_equal(world_place(w, 1, 0, 500, 200, 0), 0); /* where the line was: white paper now */
    steps(w, &io, 1, 1);
    assert_int_equal(io.raw[1], 711);
    world_free(w);
    world_free(paper);
}

static void same_steps_same_poses(void **state)
{
    struct world *a = load("arena.json"), *b = load("arena.json");
    struct world_brick_io io = { .motor = { FWD7, 0, 1u << 3 | 3u } };
    char pa[2048], pb[2048];
    (void)state;
    steps(a, &io, 1, 4000);
    steps(b, &io, 1, 4000);
    world_pose_json(a, pa, sizeof pa);
    world_pose_json(b, pb, sizeof pb);
    assert_string_equal(pa, pb);
    assert_null(strstr(pa, "\"x\":300.0,\"y\":300.0")); /* it moved */
    world_free(a);
    world_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(light_reads_white_paper_and_black_line),
        cmocka_unit_test(bumpers_press_on_a_wall_only),
        cmocka_unit_test(rotation_counts_sixteen_a_turn_forwards),
        cmocka_unit_test(light_noise_is_seeded),
        cmocka_unit_test(float_coasts_and_brake_stops),
        cmocka_unit_test(robot_pushes_a_sleeping_obstacle),
        cmocka_unit_test(placing_checks_the_floor_and_the_index),
        cmocka_unit_test(scene_json_has_the_panel_shapes),
        cmocka_unit_test(floor_picture_replaced_or_refused),
        cmocka_unit_test(same_steps_same_poses),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
