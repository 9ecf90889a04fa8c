/* libball::render: headless snapshot frames of a libball scene, drawn with
 * plain fixed-function OpenGL into memory through OSMesa (Mesa's llvmpipe:
 * no display, no GPU, no window system), written as PNG through libpng.
 * A component library beside the scene loader; libball itself stays
 * libm-only. See docs/render.md.
 *
 * Two ways in:
 *   - from plain data (a watcher, a server, anything that knows where the
 *     ball, the rackets and the recent events are): fill a ball_frame and
 *     call ball_render_draw. Nothing here steps a sim.
 *   - from a scene file: ball_replay plays the scene frame by frame as
 *     ballsim does (ball_scene_run) and fills the ball_frame at the times
 *     asked for, with a trail and the recent events.
 *
 * Like the core, nothing here prints, aborts or exits: every call returns a
 * ball_status. Unlike the core, it allocates (the pixel buffers, the GL
 * context): a renderer is created and destroyed. */
#ifndef BALL_RENDER_H
#define BALL_RENDER_H

#include <stddef.h>

#include "ball/ball.h"
#include "ball/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BALL_RENDER_MIN_SIZE 16    /* pixels, each side */
#define BALL_RENDER_MAX_SIZE 2048  /* pixels, each side */

/* ---- cameras ------------------------------------------------------------- */

/* Cameras every scene has, placed from its model (net, walls, rackets'
 * targets, the ball's start): the court's long axis is the one across the
 * net (else the longer side of the scene). */
typedef enum ball_camera_preset {
  BALL_CAMERA_SIDE = 0,  /* from the side, 28 degrees up, the long axis left to right */
  BALL_CAMERA_TOP,       /* straight down, the long axis left to right */
  BALL_CAMERA_BEHIND0,   /* behind player 0: the low end of the long axis, looking along it */
  BALL_CAMERA_BEHIND1,   /* behind player 1: the high end, looking back */
  BALL_CAMERA_PRESET_COUNT
} ball_camera_preset;

/* "side", "top", "behind0", "behind1"; NULL for a value out of range. */
BALL_API const char *ball_camera_preset_name(ball_camera_preset preset);

/* A preset for model, framed for an image of aspect = width / height. */
BALL_API ball_status ball_camera_from_preset(const ball_model *model, ball_camera_preset preset, double aspect,
                                             ball_camera *out);

/* The same, framing the floor of ball_floor_layout_court (a court given
 * instead of the one the net implies). BALL_EINVAL for NULL, BALL_ENONFINITE
 * or BALL_ERANGE for a court ball_floor_layout_court refuses. */
BALL_API ball_status ball_camera_from_preset_court(const ball_model *model, const double court[4],
                                                   ball_camera_preset preset, double aspect, ball_camera *out);

/* The camera called name: one of the scene's render.cameras (looked up
 * first, so a scene may redefine a preset's name) or a preset. BALL_ENOTFOUND
 * for an unknown name. */
BALL_API ball_status ball_camera_find(const ball_scene *scene, const char *name, double aspect, ball_camera *out);

/* Where point p appears in a width x height image from cam: *px to the
 * right, *py down, in pixels from the image's top-left corner (the centre of
 * pixel (i, j) is (i + 0.5, j + 0.5)); *depth (may be NULL) is the distance
 * in front of the camera, m. The same matrices the renderer draws with.
 * BALL_ERANGE for a point behind the camera. */
BALL_API ball_status ball_camera_project(const ball_camera *cam, int width, int height, ball_vec3 p, double *px,
                                         double *py, double *depth);

/* ---- the floor ----------------------------------------------------------- */

#define BALL_FLOOR_MAX_LINES 8  /* court lines */

/* The floor every picture of a model shows (the table "What is drawn" of
 * docs/render.md): a ground quad over the scene's area; with a net, a court
 * (a tennis court scaled to the net's width) and its lines; without one, a
 * grid. Rectangles are {x0, z0, x1, z1} on the floor plane, m. For a client
 * that draws the court itself (the spectator page) as the renderer does. */
typedef struct ball_floor_layout {
  double level;                               /* y of the floor, m */
  double ground[4];                           /* the floor quad */
  int has_court;                              /* 1: court and lines; 0: the grid */
  double court[4];                            /* the court quad (has_court) */
  int n_lines;                                /* [0, BALL_FLOOR_MAX_LINES] */
  double lines[BALL_FLOOR_MAX_LINES][4];      /* court lines, each a thin rectangle */
  double grid_step, grid_width;               /* the grid (no court): lines every grid_step m, this wide */
} ball_floor_layout;

/* The floor of a model as ball_render_draw draws it. BALL_EINVAL for NULL. */
BALL_API ball_status ball_floor_layout_of(const ball_model *model, ball_floor_layout *out);

/* The floor of a model around a court given instead of the one its net
 * implies: court = {x0, z0, x1, z1} on the floor plane, x0 < x1, z0 < z1
 * (a ball server's rules judge a court of their own: MatchInfo's court_x and
 * court_z). The ground grows to hold it; the lines are a tennis court's on
 * it: the outer lines and, with a net across the court, the service lines at
 * 6.40 / 11.885 of each half from the net and the centre line between them.
 * BALL_EINVAL for NULL, BALL_ENONFINITE for a NaN or infinite corner,
 * BALL_ERANGE for an empty court or a corner beyond BALL_MAX_COORD. */
BALL_API ball_status ball_floor_layout_court(const ball_model *model, const double court[4], ball_floor_layout *out);

/* ---- the palette ---------------------------------------------------------- */

/* A colour: red, green and blue, each in [0, 1]. */
typedef struct ball_rgb {
  float r, g, b;
} ball_rgb;

/* The renderer's colours and opacities (docs/render.md, "What is drawn"):
 * fixed, so that frames compare. A client that draws a court itself (the
 * spectator page) takes its colours from here. */
typedef struct ball_palette {
  ball_rgb sky;                               /* the background */
  ball_rgb ground;                            /* the floor quad */
  ball_rgb court;                             /* the court (with a net) */
  ball_rgb line;                              /* court lines; the net's tape and outline */
  ball_rgb grid;                              /* the 1 m grid (without a net) */
  ball_rgb net;                               /* the net; the ball's shadow; racket rims */
  ball_rgb wall;                              /* walls */
  ball_rgb wall_edge;                         /* walls' outlines */
  ball_rgb ball;                              /* the ball (a colour nothing else has) */
  ball_rgb trail;                             /* the ball's trail */
  ball_rgb rackets[BALL_MAX_RACKETS];         /* racket i's disc */
  ball_rgb markers[BALL_EVENT_KIND_COUNT];    /* an event's marker, by ball_event_kind */
  float net_alpha;                            /* opacity of the net, [0, 1] */
  float tape_alpha;                           /* of the net's tape */
  float wall_alpha;                           /* of a wall */
  float shadow_alpha;                         /* of the ball's shadow */
} ball_palette;

/* The palette ball_render_draw draws with. BALL_EINVAL for NULL. */
BALL_API ball_status ball_render_palette(ball_palette *out);

/* ---- frames from plain data ------------------------------------------------ */

typedef struct ball_render_racket {
  int visible;        /* 0: not drawn (no pose known) */
  ball_vec3 center;   /* disc centre, m */
  ball_vec3 normal;   /* disc normal, any length > 0; the radius is the model's */
} ball_render_racket;

/* Everything one picture shows besides the model's fixed geometry. */
typedef struct ball_frame {
  double time;                                  /* s; informative, not drawn */
  ball_vec3 ball;                               /* ball centre, m */
  int n_rackets;                                /* [0, model->n_rackets] */
  ball_render_racket rackets[BALL_MAX_RACKETS];
  int n_trail;                                  /* >= 0 */
  const ball_vec3 *trail;                       /* n_trail recent ball centres, oldest first, m */
  int n_events;                                 /* >= 0 */
  const ball_event *events;                     /* a marker at each event's point (floor, net, wall, racket) */
} ball_frame;

/* An OSMesa context and its pixels. */
typedef struct ball_renderer ball_renderer;

/* A renderer for width x height images (each in [BALL_RENDER_MIN_SIZE,
 * BALL_RENDER_MAX_SIZE]). BALL_ENOMEM if OSMesa or the buffers cannot be had.
 * llvmpipe reads LP_NUM_THREADS when the first context is made. */
BALL_API ball_status ball_renderer_create(int width, int height, ball_renderer **out);

/* Frees the renderer; NULL is harmless. */
BALL_API void ball_renderer_destroy(ball_renderer *renderer);

/* The entry point for a watcher (ball-watch) or any client with plain data:
 * draws the model's floor (court lines when it has a net, a 1 m grid
 * otherwise), net and walls, the frame's rackets as oriented discs, the ball
 * as a lit sphere with its shadow on the floor, the trail and the event
 * markers, from cam, with fixed lighting. The ball is drawn with the model's
 * radius, but never under 2 pixels of radius (a point ball
 * would not show). Draw calls on one renderer must come from one thread at a
 * time. BALL_EINVAL / BALL_ENONFINITE / BALL_ERANGE for a bad argument (the
 * pixels are then unchanged).
 *
 * A watcher fills the frame from what it received: ball from
 * ball_segment_eval(model, &latest_segment, t), each racket from its latest
 * pose sample (visible 0 until one came), trail from the centres it kept,
 * events from the collision events of the last second or so. */
BALL_API ball_status ball_render_draw(ball_renderer *renderer, const ball_model *model, const ball_camera *cam,
                                      const ball_frame *frame);

/* The last drawn picture: *rgb (width * height * 3 bytes, rows top first)
 * stays valid until the next draw or the destroy. */
BALL_API ball_status ball_render_pixels(const ball_renderer *renderer, const unsigned char **rgb, int *width,
                                        int *height);

/* ---- frames from a scene ----------------------------------------------------- */

#define BALL_REPLAY_MAX_TRAIL 4096  /* frames a trail can hold */
#define BALL_REPLAY_MAX_EVENTS 256  /* recent events kept for markers */

/* A scene played forward to the times asked for, with what a frame shows.
 * About 200 kB: allocate it statically or on the heap. */
typedef struct ball_replay {
  ball_scene scene;                               /* a copy */
  ball_scene_run run;                             /* stepped as ballsim steps it */
  double trail;                                   /* s of trail, [0, 60] */
  double markers;                                 /* s a marker stays, [0, 60] */
  int trail_start, n_trail;                       /* ring of the frames' ball centres */
  ball_vec3 trail_points[BALL_REPLAY_MAX_TRAIL];
  double trail_times[BALL_REPLAY_MAX_TRAIL];      /* s */
  ball_vec3 frame_trail[BALL_REPLAY_MAX_TRAIL + 1];  /* the last frame's trail, in order */
  int event_start, n_events;                      /* ring of recent events */
  ball_event events[BALL_REPLAY_MAX_EVENTS];
  ball_event frame_events[BALL_REPLAY_MAX_EVENTS];   /* the last frame's markers, in order */
} ball_replay;

/* Starts a replay of scene (checked by ball_model_check) with trail and
 * markers seconds (each in [0, 60]). */
BALL_API ball_status ball_replay_init(ball_replay *replay, const ball_scene *scene, double trail, double markers);

/* Steps whole frames (dt = frame_time * time_base) while the next frame ends
 * at or before t (to 1e-9 s), then fills frame with the ball on the current
 * segment at t (eq 3: where a client evaluating the segment shows it; at a
 * frame's time exactly the sim's state), each racket's pose as the sim
 * estimates it at t (ball_racket_estimate; not drawn without one), the frame
 * centres of the last `trail` seconds and the events of the last `markers`
 * seconds. t must not go back: BALL_ERANGE for t before the last time asked.
 * frame points into replay, valid until the next call. */
BALL_API ball_status ball_replay_frame(ball_replay *replay, double t, ball_frame *frame);

/* ---- PNG files and image comparison ----------------------------------------- */

/* Writes 8-bit RGB, rows top first, through libpng. BALL_EIO if the file
 * cannot be written; errno then holds the reason (from fopen or fclose). */
BALL_API ball_status ball_png_write(const char *path, const unsigned char *rgb, int width, int height);

/* Reads a PNG (any bit depth or colour type, turned into 8-bit RGB on a
 * black background) into *rgb, allocated with malloc: free it with free().
 * BALL_EIO if it cannot be opened, BALL_EPARSE if it is not a PNG. */
BALL_API ball_status ball_png_read(const char *path, unsigned char **rgb, int *width, int *height);

/* What ball_image_compare found. */
typedef struct ball_image_diff {
  long differing;   /* pixels with some channel more than the tolerance apart */
  int max_diff;     /* largest difference of one channel over all pixels, [0, 255] */
  long first_x, first_y;  /* the first differing pixel (row order), -1 if none */
} ball_image_diff;

/* Compares two RGB images of one size channel by channel: a pixel differs
 * when some channel is more than tolerance ([0, 255]) apart. If diff_rgb is
 * not NULL it gets a picture of the differences (width * height * 3 bytes):
 * the expected image dimmed to a quarter, differing pixels in red. */
BALL_API ball_status ball_image_compare(const unsigned char *expected, const unsigned char *actual, int width,
                                        int height, int tolerance, ball_image_diff *out, unsigned char *diff_rgb);

#ifdef __cplusplus
}
#endif

#endif /* BALL_RENDER_H */
