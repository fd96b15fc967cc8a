/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The checks of the panel's world requests (host_sim/panel_world_args.c), without HTTP or a simulation: what a drag
 * (POST /world/place) may say, which scene names may be asked for (they become a file name), what a floor upload must
 * start with, the list of scenes, and what is read from the scene's JSON to check a drag against.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "panel.h"

/* The contract's example scene (world.h): a 1600 x 1200 mm floor, a movable box and a fixed circle, two robots. */
static const char scene_json[] =
    "{\"scene\":\"arena\",\"floor\":{\"w\":1600,\"h\":1200,\"version\":0},"
    "\"walls\":[{\"x1\":0,\"y1\":0,\"x2\":1600,\"y2\":0,\"t\":20}],"
    "\"obstacles\":[{\"i\":0,\"shape\":\"box\",\"w\":100,\"h\":60,\"color\":\"#cc3333\",\"movable\":true},"
    "{\"i\":1,\"shape\":\"circle\",\"r\":50,\"color\":\"#3355cc\",\"movable\":false}],"
    "\"robots\":[{\"i\":0,\"brick\":0,\"name\":\"roverbot\",\"w\":120,\"l\":160,\"wheel_d\":43.2,\"track\":110,"
    "\"sensors\":[{\"input\":2,\"kind\":\"light\",\"x\":70,\"y\":0}]},"
    "{\"i\":1,\"brick\":1,\"name\":\"roverbot\",\"w\":120,\"l\":160,\"wheel_d\":43.2,\"track\":110,\"sensors\":[]}]}";

static struct panel_world_limits limits(void)
{
    struct panel_world_limits lim;
    assert_int_equal(panel_world_limits_parse(scene_json, &lim), 0);
    return lim;
}

static void the_scene_json_gives_floor_counts_and_movable_obstacles(void **state)
{
    struct panel_world_limits lim = limits();
    (void)state;
    assert_string_equal(lim.scene, "arena");
    assert_true(lim.floor_w == 1600 && lim.floor_h == 1200);
    assert_int_equal(lim.robots, 2);
    assert_int_equal(lim.obstacles, 2);
    assert_int_equal(lim.movable[0], 1);
    assert_int_equal(lim.movable[1], 0);
}

static void a_scene_without_a_floor_is_not_one(void **state)
{
    struct panel_world_limits lim;
    (void)state;
    assert_int_equal(panel_world_limits_parse("{\"scene\":\"x\",\"robots\":[]}", &lim), -1);
    assert_int_equal(panel_world_limits_parse("{\"floor\":{\"w\":0,\"h\":5}}", &lim), -1);
    assert_int_equal(panel_world_limits_parse("not json", &lim), -1);
    assert_int_equal(lim.robots, 0);
}

static void a_robot_is_placed_with_its_heading_brought_into_0_360(void **state)
{
    struct panel_world_limits lim = limits();
    struct panel_place p;
    const char *why = NULL;
    (void)state;
    assert_int_equal(panel_place_parse("1", NULL, "812.5", "0", "-90", &lim, &p, &why), 0);
    assert_true(p.is_robot && p.index == 1 && p.x == 812.5 && p.y == 0 && p.h == 270);
    assert_int_equal(panel_place_parse("0", NULL, "1600", "1200", "450", &lim, &p, &why), 0);
    assert_true(p.x == 1600 && p.y == 1200 && p.h == 90);
    assert_int_equal(panel_place_parse(NULL, "0", "1e2", "+3", "0", &lim, &p, &why), 0);
    assert_true(!p.is_robot && p.index == 0 && p.x == 100 && p.y == 3 && p.h == 0);
}

/* Each refusal: -1 and a reason. */
static void refused(const char *robot, const char *obstacle, const char *x, const char *y, const char *h,
                    const char *reason_starts)
{
    struct panel_world_limits lim = limits();
    struct panel_place p;
    const char *why = NULL;
    assert_int_equal(panel_place_parse(robot, obstacle, x, y, h, &lim, &p, &why), -1);
    assert_non_null(why);
    assert_memory_equal(why, reason_starts, strlen(reason_starts));
}

static void a_place_names_one_existing_thing(void **state)
{
    (void)state;
    refused(NULL, NULL, "1", "1", "0", "expected robot=N or obstacle=N");
    refused("0", "0", "1", "1", "0", "expected robot=N or obstacle=N");
    refused("2", NULL, "1", "1", "0", "robot: no such robot");
    refused("-1", NULL, "1", "1", "0", "robot: no such robot");
    refused("0x1", NULL, "1", "1", "0", "robot: no such robot");
    refused("", NULL, "1", "1", "0", "robot: no such robot");
    refused(NULL, "2", "1", "1", "0", "obstacle: no such obstacle");
    refused(NULL, "1", "1", "1", "0", "obstacle: this one is fixed");
}

static void a_place_is_on_the_floor_in_plain_decimals(void **state)
{
    (void)state;
    refused("0", NULL, "1600.1", "1", "0", "x, y:");
    refused("0", NULL, "-0.5", "1", "0", "x, y:");
    refused("0", NULL, "1", "1200.01", "0", "x, y:");
    refused("0", NULL, NULL, "1", "0", "x, y:");
    refused("0", NULL, "", "1", "0", "x, y:");
    refused("0", NULL, "inf", "1", "0", "x, y:");
    refused("0", NULL, "nan", "1", "0", "x, y:");
    refused("0", NULL, "0x10", "1", "0", "x, y:");
    refused("0", NULL, "12abc", "1", "0", "x, y:");
    refused("0", NULL, "1 ", "1", "0", "x, y:");
    refused("0", NULL, "1", "1", NULL, "h:");
    refused("0", NULL, "1", "1", "1e400", "h:");
    refused("0", NULL, "1", "1", "36001", "h:");
}

static void a_scene_name_is_a_plain_file_name(void **state)
{
    char longest[PANEL_SCENE_NAME_MAX + 2];
    (void)state;
    assert_true(panel_scene_name_ok("oval"));
    assert_true(panel_scene_name_ok("two_robots"));
    assert_true(panel_scene_name_ok("Maze-2"));
    assert_false(panel_scene_name_ok(NULL));
    assert_false(panel_scene_name_ok(""));
    assert_false(panel_scene_name_ok("../etc/passwd"));
    assert_false(panel_scene_name_ok("a/b"));
    assert_false(panel_scene_name_ok(".hidden"));
    assert_false(panel_scene_name_ok("-v"));
    assert_false(panel_scene_name_ok("a b"));
    assert_false(panel_scene_name_ok("oval.json"));
    memset(longest, 'a', sizeof longest);
    longest[PANEL_SCENE_NAME_MAX] = 0;
    assert_true(panel_scene_name_ok(longest));
    longest[PANEL_SCENE_NAME_MAX] = 'a';
    longest[PANEL_SCENE_NAME_MAX + 1] = 0;
    assert_false(panel_scene_name_ok(longest));
}

static void a_floor_picture_starts_with_the_png_signature(void **state)
{
    /* PNG specification, 5.2: 137 80 78 71 13 10 26 10 */
    static const unsigned char png[] = { 137, 80, 78, 71, 13, 10, 26, 10, 0, 0, 0, 13, 'I', 'H', 'D', 'R' };
    static const unsigned char gif[] = "GIF89a....";
    (void)state;
    assert_null(panel_png_problem(png, sizeof png));
    assert_non_null(panel_png_problem(png, 0));
    assert_non_null(panel_png_problem(png, 7));
    assert_non_null(panel_png_problem(gif, sizeof gif));
}

static void touch(const char *dir, const char *name)
{
    char path[512];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("{}\n", f);
    fclose(f);
}

static void the_scene_list_holds_the_json_files_with_good_names_sorted(void **state)
{
    char dir[] = "/tmp/panel_scenes.XXXXXX", buf[256], path[512];
    static const char *const files[] = { "oval.json", "arena.json", "notes.txt", "bad name.json", ".json",
                                         "two_robots.json" };
    size_t i, n;
    (void)state;
    assert_non_null(mkdtemp(dir));
    for (i = 0; i < sizeof files / sizeof files[0]; i++)
        touch(dir, files[i]);
    n = panel_scene_list_json(dir, "oval", buf, sizeof buf);
    assert_string_equal(buf, "{\"current\":\"oval\",\"scenes\":[\"arena\",\"oval\",\"two_robots\"]}");
    assert_int_equal(n, strlen(buf));
    panel_scene_list_json(dir, "../x", buf, sizeof buf);
    assert_string_equal(buf, "{\"current\":\"\",\"scenes\":[\"arena\",\"oval\",\"two_robots\"]}");
    assert_int_equal(panel_scene_list_json(dir, "oval", buf, 40), 0); /* does not fit */
    for (i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        unlink(path);
    }
    rmdir(dir);
    panel_scene_list_json(dir, "oval", buf, sizeof buf); /* gone: an empty list, not an error */
    assert_string_equal(buf, "{\"current\":\"oval\",\"scenes\":[]}");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_scene_json_gives_floor_counts_and_movable_obstacles),
        cmocka_unit_test(a_scene_without_a_floor_is_not_one),
        cmocka_unit_test(a_robot_is_placed_with_its_heading_brought_into_0_360),
        cmocka_unit_test(a_place_names_one_existing_thing),
        cmocka_unit_test(a_place_is_on_the_floor_in_plain_decimals),
        cmocka_unit_test(a_scene_name_is_a_plain_file_name),
        cmocka_unit_test(a_floor_picture_starts_with_the_png_signature),
        cmocka_unit_test(the_scene_list_holds_the_json_files_with_good_names_sorted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
