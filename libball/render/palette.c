/* The renderer's colours, in one place: ball_render_draw draws with them and
 * a client that draws a court itself (the spectator page, through the court
 * message of ball-watch --http) reads them with ball_render_palette. */
#include "ball/render.h"

static const ball_palette palette = {
    {0.80f, 0.86f, 0.92f}, /* sky */
    {0.30f, 0.52f, 0.32f}, /* ground */
    {0.22f, 0.42f, 0.62f}, /* court */
    {0.95f, 0.95f, 0.95f}, /* line */
    {0.24f, 0.44f, 0.27f}, /* grid */
    {0.12f, 0.12f, 0.14f}, /* net */
    {0.78f, 0.66f, 0.50f}, /* wall */
    {0.45f, 0.35f, 0.25f}, /* wall_edge */
    {0.95f, 0.90f, 0.10f}, /* ball */
    {1.00f, 0.55f, 0.05f}, /* trail */
    {{0.85f, 0.15f, 0.15f}, {0.15f, 0.30f, 0.85f}, {0.85f, 0.45f, 0.85f}, {0.20f, 0.75f, 0.75f}}, /* rackets */
    {{1.00f, 1.00f, 1.00f},  /* floor: a white ring on the floor */
     {1.00f, 0.10f, 0.80f},  /* net: a magenta ring in the net */
     {1.00f, 0.45f, 0.00f},  /* wall: an orange ring on the wall */
     {0.95f, 0.10f, 0.10f}}, /* racket: a red cross */
    0.45f,                   /* net_alpha */
    0.95f,                   /* tape_alpha */
    0.55f,                   /* wall_alpha */
    0.45f,                   /* shadow_alpha */
};

ball_status ball_render_palette(ball_palette *out) {
  if (!out) return BALL_EINVAL;
  *out = palette;
  return BALL_OK;
}
