/* PNG files through libpng (its simplified API) and image comparison. */
#include <errno.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "ball/render.h"

ball_status ball_png_write(const char *path, const unsigned char *rgb, int width, int height) {
  png_image img;
  FILE *f;
  int ok, saved;
  if (!path || !rgb) return BALL_EINVAL;
  if (width < 1 || height < 1) return BALL_ERANGE;
  f = fopen(path, "wb");
  if (!f) return BALL_EIO;
  memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  img.width = (png_uint_32)width;
  img.height = (png_uint_32)height;
  img.format = PNG_FORMAT_RGB;
  ok = png_image_write_to_stdio(&img, f, 0, rgb, width * 3, NULL);
  saved = errno;
  png_image_free(&img);
  if (fclose(f) != 0) ok = 0;
  else errno = saved;
  return ok ? BALL_OK : BALL_EIO;
}

ball_status ball_png_read(const char *path, unsigned char **rgb, int *width, int *height) {
  png_image img;
  png_color black;
  unsigned char *buf;
  FILE *f;
  if (!path || !rgb || !width || !height) return BALL_EINVAL;
  f = fopen(path, "rb");
  if (!f) return BALL_EIO;
  memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_stdio(&img, f)) {
    fclose(f);
    return BALL_EPARSE;
  }
  img.format = PNG_FORMAT_RGB;
  if (img.width > 65536 || img.height > 65536) {
    png_image_free(&img);
    fclose(f);
    return BALL_ERANGE;
  }
  buf = (unsigned char *)malloc(PNG_IMAGE_SIZE(img));
  if (!buf) {
    png_image_free(&img);
    fclose(f);
    return BALL_ENOMEM;
  }
  black.red = black.green = black.blue = 0;
  if (!png_image_finish_read(&img, &black, buf, 0, NULL)) {
    free(buf);
    png_image_free(&img);
    fclose(f);
    return BALL_EPARSE;
  }
  fclose(f);
  *rgb = buf;
  *width = (int)img.width;
  *height = (int)img.height;
  return BALL_OK;
}

ball_status ball_image_compare(const unsigned char *expected, const unsigned char *actual, int width, int height,
                               int tolerance, ball_image_diff *out, unsigned char *diff_rgb) {
  ball_image_diff d;
  long i, n;
  if (!expected || !actual || !out) return BALL_EINVAL;
  if (width < 1 || height < 1 || tolerance < 0 || tolerance > 255) return BALL_ERANGE;
  d.differing = 0;
  d.max_diff = 0;
  d.first_x = d.first_y = -1;
  n = (long)width * height;
  for (i = 0; i < n; ++i) {
    int c, worst = 0;
    for (c = 0; c < 3; ++c) {
      int e = abs((int)expected[3 * i + c] - (int)actual[3 * i + c]);
      if (e > worst) worst = e;
    }
    if (worst > d.max_diff) d.max_diff = worst;
    if (worst > tolerance) {
      if (d.differing == 0) {
        d.first_x = i % width;
        d.first_y = i / width;
      }
      d.differing++;
    }
    if (diff_rgb) {
      if (worst > tolerance) {
        diff_rgb[3 * i] = 255;
        diff_rgb[3 * i + 1] = 0;
        diff_rgb[3 * i + 2] = 0;
      } else {
        for (c = 0; c < 3; ++c) diff_rgb[3 * i + c] = (unsigned char)(expected[3 * i + c] / 4);
      }
    }
  }
  *out = d;
  return BALL_OK;
}
