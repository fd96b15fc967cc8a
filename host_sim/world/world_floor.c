/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The floor picture: decoded once with libpng's simplified API into grey levels (what a light sensor's single
 * photo-transistor can tell apart), and kept as the PNG bytes it came in for the panel to show.
 */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "world_model.h"

#define FLOOR_MAX_PIXELS (4096u * 4096u) /* a floor picture larger than this is a mistake, not a floor */

/* The table of sums: sum[j][i] is the sum of the grey levels above and left of pixel (i, j), so that a rectangle's
 * sum costs four reads whatever its size - a light sensor is read every simulated millisecond. */
static void floor_sums(struct world_floor *f)
{
    unsigned i, j, w = f->px_w + 1;
    free(f->sum);
    f->sum = calloc((size_t)w * (f->px_h + 1), sizeof *f->sum);
    if (!f->sum)
        abort();
    for (j = 0; j < f->px_h; j++) {
        unsigned row = 0;
        for (i = 0; i < f->px_w; i++) {
            row += f->grey[(size_t)j * f->px_w + i];
            f->sum[(size_t)(j + 1) * w + i + 1] = f->sum[(size_t)j * w + i + 1] + row;
        }
    }
}

int floor_decode(struct world_floor *f, const unsigned char *png, size_t len, char *err, size_t errlen)
{
    png_image img;
    unsigned char *grey, *copy;

    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&img, png, len)) {
        snprintf(err, errlen, "not a PNG picture (%s)", img.message);
        return -1;
    }
    if (img.width == 0 || img.height == 0 || (unsigned long long)img.width * img.height > FLOOR_MAX_PIXELS) {
        png_image_free(&img);
        snprintf(err, errlen, "a PNG of %ux%u pixels (1 to %u pixels wanted)", img.width, img.height,
                 FLOOR_MAX_PIXELS);
        return -1;
    }
    img.format = PNG_FORMAT_GRAY;
    grey = malloc(PNG_IMAGE_SIZE(img));
    copy = malloc(len);
    if (!grey || !copy)
        abort();
    /* Transparent parts are composed onto white paper. */
    {
        png_color white = { 255, 255, 255 };
        if (!png_image_finish_read(&img, &white, grey, 0, NULL)) {
            snprintf(err, errlen, "a broken PNG picture (%s)", img.message);
            free(grey);
            free(copy);
            return -1;
        }
    }
    memcpy(copy, png, len);
    free(f->grey);
    free(f->png);
    f->grey = grey;
    f->png = copy;
    f->png_len = len;
    f->px_w = img.width;
    f->px_h = img.height;
    f->version++;
    floor_sums(f);
    return 0;
}

void floor_free(struct world_floor *f)
{
    free(f->grey);
    free(f->png);
    free(f->sum);
    f->sum = NULL;
    f->grey = NULL;
    f->png = NULL;
}

static long clamp(long v, long lo, long hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* The mean grey level under a light sensor's spot of radius r mm around (x, y), 0 black - 1 white, taken over the
 * square of the same area (side r * sqrt(pi)); what lies off the floor reads as black (nothing reflected). The
 * picture is stretched over the floor's size in mm. */
double floor_brightness(const struct world_floor *f, double x, double y, double r)
{
    double half = r * 0.886226925452758, sx = f->px_w / f->w_mm, sy = f->px_h / f->h_mm; /* sqrt(pi) / 2 */
    long x0 = (long)floor((x - half) * sx + 0.5), x1 = (long)floor((x + half) * sx + 0.5);
    long y0 = (long)floor((f->h_mm - y - half) * sy + 0.5), y1 = (long)floor((f->h_mm - y + half) * sy + 0.5);
    long area, cx0, cx1, cy0, cy1;
    size_t w = f->px_w + 1;

    if (x1 <= x0)
        x1 = x0 + 1;
    if (y1 <= y0)
        y1 = y0 + 1;
    area = (x1 - x0) * (y1 - y0);
    cx0 = clamp(x0, 0, f->px_w);
    cx1 = clamp(x1, 0, f->px_w);
    cy0 = clamp(y0, 0, f->px_h);
    cy1 = clamp(y1, 0, f->px_h);
    return (double)(f->sum[cy1 * w + cx1] - f->sum[cy0 * w + cx1] - f->sum[cy1 * w + cx0] + f->sum[cy0 * w + cx0]) /
           (255.0 * area);
}
