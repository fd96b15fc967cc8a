/* SPDX-License-Identifier: MPL-2.0 */
/*
 * floorgen: draws the floor pictures the shipped scenes use, so that every pixel of them is the project's own.
 * `floorgen DIR` writes DIR/testpad.png and DIR/paper.png. Their outputs are committed next to the scenes (a fresh
 * clone, the package and an installed rcxsim all find them without running this); CTest's world.floors checks that
 * this program still draws exactly what is committed.
 *
 * testpad.png: 1400 x 1000 mm at 2 mm a pixel, white paper with a black oval line 20 mm wide - two half circles of
 * radius 300 mm (to the line's middle) around (400, 500) and (1000, 500) joined by straights at y = 200 and 800.
 * paper.png: plain white paper, for scenes whose floor is only something to stand on.
 */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MM_PER_PX 2.0

/* The test pad's oval, in mm: the distance of (x, y) from the line's middle. */
static double oval_distance(double x, double y)
{
    const double cx0 = 400, cx1 = 1000, cy = 500, radius = 300;
    double cx = x < cx0 ? cx0 : x > cx1 ? cx1 : x;
    return fabs(hypot(x - cx, y - cy) - radius);
}

static int write_png(const char *dir, const char *name, unsigned w, unsigned h, const unsigned char *grey)
{
    char path[4096];
    png_image img;

    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = w;
    img.height = h;
    img.format = PNG_FORMAT_GRAY;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!png_image_write_to_file(&img, path, 0, grey, 0, NULL)) {
        fprintf(stderr, "floorgen: %s: %s\n", path, img.message);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    const unsigned w = (unsigned)(1400 / MM_PER_PX), h = (unsigned)(1000 / MM_PER_PX), sub = 4;
    unsigned char *grey = malloc((size_t)w * h);
    unsigned i, j, a, b;
    int status;

    if (argc != 2 || !grey) {
        fprintf(stderr, "usage: floorgen DIR\n");
        return 2;
    }
    /* Each pixel is the share of its 4 x 4 sample points off the line: the line's edges are anti-aliased. */
    for (j = 0; j < h; j++) {
        for (i = 0; i < w; i++) {
            unsigned white = 0;
            for (b = 0; b < sub; b++)
                for (a = 0; a < sub; a++) {
                    double x = (i + (a + 0.5) / sub) * MM_PER_PX, y = 1000 - (j + (b + 0.5) / sub) * MM_PER_PX;
                    white += oval_distance(x, y) > 10.0;
                }
            grey[(size_t)j * w + i] = (unsigned char)(white * 255 / (sub * sub));
        }
    }
    status = write_png(argv[1], "testpad.png", w, h, grey);
    memset(grey, 255, (size_t)w * h);
    status |= write_png(argv[1], "paper.png", 8, 8, grey);
    free(grey);
    return status ? 1 : 0;
}
