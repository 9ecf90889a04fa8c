/* ballrender: snapshot frames of a libball scene as PNG files, headless
 * (OSMesa). The scene is played as ballsim plays it (ball_scene_run), so the
 * ball is drawn where libball puts it. See docs/render.md. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ball/render.h"
#include "ball/scene.h"

#define TOOL_NAME "ballrender"
#include "args.h"

#define MAX_FRAMES 10000
#define MAX_TIME 86400.0 /* s */
#define DEFAULT_WIDTH 640
#define DEFAULT_HEIGHT 480

typedef struct options {
  const char *scene_path;
  const char *times_text;  /* --times */
  double every;            /* --every, 0: not given */
  double duration;         /* --duration, 0: the scene's */
  const char *camera;
  int width, height;
  const char *out_dir;
  double trail, markers;   /* < 0: the scene's */
} options;

static void print_help(FILE *f) {
  fprintf(f,
          "usage: ballrender SCENE (--times T1,T2,... | --every S [--duration S])\n"
          "                  [--camera NAME] [--size WxH] [--trail S] [--markers S] --out DIR\n"
          "       ballrender --help\n"
          "\n"
          "Renders snapshot frames of a libball scene headless (OSMesa, no display or\n"
          "GPU needed): one PNG per time, DIR/tSSSS.mmm.png (the time in seconds with\n"
          "milliseconds, e.g. t0001.250.png). The scene is stepped exactly as ballsim\n"
          "steps it (frames of frame_time * time_base, scripted racket samples fed\n"
          "before each step); a time between two frames shows the ball on the current\n"
          "flight segment (eq 3), as a client evaluating the segment would.\n"
          "\n"
          "  SCENE            a YAML scene file (docs/scenes.md, docs/render.md)\n"
          "  --times LIST     comma-separated times in s, each in [0, 86400]; any order\n"
          "  --every S        a frame every S s (S > 0) from 0 to the duration\n"
          "  --duration S     with --every: how long, S > 0; default the scene's duration\n"
          "  --camera NAME    side (default), top, behind0, behind1, or a camera of the\n"
          "                   scene's render.cameras\n"
          "  --size WxH       image size in pixels, each in [16, 2048]; default 640x480\n"
          "  --trail S        draw the ball's last S s as a trail, [0, 60]; default the\n"
          "                   scene's render.trail (0: none)\n"
          "  --markers S      mark the events of the last S s, [0, 60]; default the\n"
          "                   scene's render.markers (1 s)\n"
          "  --out DIR        folder for the frames; made if missing (not its parents)\n"
          "  -h, --help       this text\n"
          "\n"
          "Output: one line per frame written:\n"
          "  frame t=T file=PATH ball=X,Y,Z pixel=PX,PY\n"
          "(the ball centre in m, to the last bit, and where it is in the image in\n"
          "pixels, x right and y down from the top-left corner).\n"
          "Exit status: 0 on success, 1 for a scene or runtime error (a scene error is\n"
          "FILE:LINE:COLUMN: FIELD: MESSAGE), 2 for bad arguments.\n");
}

static int parse_size(const char *text, int *w, int *h) {
  char *end;
  long a, b;
  if (!(*text >= '0' && *text <= '9')) return 0;
  a = strtol(text, &end, 10);
  if (*end != 'x' || !(end[1] >= '0' && end[1] <= '9')) return 0;
  b = strtol(end + 1, &end, 10);
  if (*end != '\0' || a < BALL_RENDER_MIN_SIZE || a > BALL_RENDER_MAX_SIZE || b < BALL_RENDER_MIN_SIZE ||
      b > BALL_RENDER_MAX_SIZE)
    return 0;
  *w = (int)a;
  *h = (int)b;
  return 1;
}

/* Returns -1 on success, else the exit status. */
static int parse_args(int argc, char **argv, options *o) {
  static const struct option longs[] = {
      {"times", required_argument, NULL, 't'},  {"every", required_argument, NULL, 'e'},
      {"duration", required_argument, NULL, 'd'}, {"camera", required_argument, NULL, 'c'},
      {"size", required_argument, NULL, 's'},   {"out", required_argument, NULL, 'o'},
      {"trail", required_argument, NULL, 'r'},  {"markers", required_argument, NULL, 'm'},
      {"help", no_argument, NULL, 'h'},         {NULL, 0, NULL, 0}};
  int c;
  memset(o, 0, sizeof *o);
  o->camera = "side";
  o->width = DEFAULT_WIDTH;
  o->height = DEFAULT_HEIGHT;
  o->trail = o->markers = -1.0;
  opterr = 0;
  while ((c = getopt_long(argc, argv, ":h", longs, NULL)) != -1) {
    const char *v = optarg;
    switch (c) {
      case 'h': print_help(stdout); return 0;
      case 't': o->times_text = v; break;
      case 'e':
        if (!parse_number(v, &o->every) || !(o->every > 0.0))
          return usage_error("--every: expected a number of seconds > 0, got \"%s\"", v);
        break;
      case 'd':
        if (!parse_number(v, &o->duration) || !(o->duration > 0.0) || o->duration > MAX_TIME)
          return usage_error("--duration: expected a number of seconds in (0, %.0f], got \"%s\"", MAX_TIME, v);
        break;
      case 'c': o->camera = v; break;
      case 's':
        if (!parse_size(v, &o->width, &o->height))
          return usage_error("--size: expected WxH with W and H in [%d, %d], got \"%s\"", BALL_RENDER_MIN_SIZE,
                             BALL_RENDER_MAX_SIZE, v);
        break;
      case 'o':
        if (!*v) return usage_error("--out: empty folder name");
        o->out_dir = v;
        break;
      case 'r':
      case 'm': {
        double s;
        if (!parse_number(v, &s) || !(s >= 0.0 && s <= 60.0))
          return usage_error("--%s: expected a number of seconds in [0, 60], got \"%s\"", c == 'r' ? "trail" : "markers",
                             v);
        if (c == 'r') o->trail = s;
        else o->markers = s;
        break;
      }
      case ':': return usage_error("%s needs a value", argv[optind - 1]);
      default: return usage_error("unknown option %s", argv[optind - 1]);
    }
  }
  if (optind < argc) o->scene_path = argv[optind++];
  if (optind < argc) return usage_error("more than one scene given: %s and %s", o->scene_path, argv[optind]);
  if (!o->scene_path) return usage_error("no scene given");
  if (!o->times_text && o->every == 0.0) return usage_error("give --times T1,T2,... or --every S");
  if (o->times_text && o->every > 0.0) return usage_error("give --times or --every, not both");
  if (o->duration > 0.0 && o->every == 0.0) return usage_error("--duration goes with --every");
  if (!o->out_dir) return usage_error("no --out DIR given");
  return -1;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The frames' times, sorted; returns -1 on success, else the exit status. */
static int frame_times(const options *o, double scene_duration, double *times, int *n) {
  int i;
  *n = 0;
  if (o->times_text) {
    const char *p = o->times_text;
    for (;;) {
      char item[64];
      size_t len = strcspn(p, ",");
      double t;
      if (len >= sizeof item) return usage_error("--times: \"%.*s...\" is not a time", 20, p);
      memcpy(item, p, len);
      item[len] = '\0';
      if (!parse_number(item, &t) || !(t >= 0.0 && t <= MAX_TIME))
        return usage_error("--times: expected times in s in [0, %.0f], got \"%s\"", MAX_TIME, item);
      if (*n == MAX_FRAMES) return usage_error("--times: more than %d times", MAX_FRAMES);
      times[(*n)++] = t;
      if (p[len] == '\0') break;
      p += len + 1;
    }
  } else {
    double duration = o->duration > 0.0 ? o->duration : scene_duration;
    double count = floor(duration / o->every * (1.0 + 1e-12)) + 1.0;
    if (count > MAX_FRAMES)
      return usage_error("--every %g over %g s makes %.0f frames, more than %d", o->every, duration, count, MAX_FRAMES);
    for (i = 0; i < (int)count; ++i) times[(*n)++] = i * o->every;
  }
  qsort(times, (size_t)*n, sizeof times[0], cmp_double);
  for (i = 1; i < *n; ++i)
    if (floor(times[i] * 1000.0 + 0.5) == floor(times[i - 1] * 1000.0 + 0.5))
      return usage_error("times %g and %g have the same file name (frames are named to the millisecond)",
                         times[i - 1], times[i]);
  return -1;
}

/* The folder exists (made if missing) and takes files. */
static int prepare_dir(const char *dir) {
  struct stat sb;
  if (stat(dir, &sb) != 0) {
    if (errno != ENOENT || mkdir(dir, 0777) != 0) {
      fprintf(stderr, "ballrender: --out %s: %s\n", dir, strerror(errno));
      return 0;
    }
  } else if (!S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "ballrender: --out %s: %s\n", dir, strerror(ENOTDIR));
    return 0;
  }
  if (access(dir, W_OK | X_OK) != 0) {
    fprintf(stderr, "ballrender: --out %s: %s\n", dir, strerror(errno));
    return 0;
  }
  return 1;
}

static void list_cameras(const ball_scene *scene) {
  int i;
  fprintf(stderr, "valid cameras:");
  for (i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i) fprintf(stderr, " %s", ball_camera_preset_name((ball_camera_preset)i));
  for (i = 0; i < scene->render.n_cameras; ++i) fprintf(stderr, " %s", scene->render.cameras[i].name);
  fprintf(stderr, "\n");
}

int main(int argc, char **argv) {
  options o;
  static ball_scene scene;
  static ball_replay replay; /* about 200 kB: off the stack */
  static double times[MAX_FRAMES];
  ball_camera cam;
  ball_renderer *renderer = NULL;
  ball_status st;
  int rc, n_times, i;

  rc = parse_args(argc, argv, &o);
  if (rc >= 0) return rc;

  if (!load_scene(o.scene_path, &scene)) return 1;
  rc = frame_times(&o, scene.duration, times, &n_times);
  if (rc >= 0) return rc;
  st = ball_camera_find(&scene, o.camera, (double)o.width / o.height, &cam);
  if (st == BALL_ENOTFOUND) {
    fprintf(stderr, "ballrender: --camera: no camera \"%s\" (see ballrender --help)\n", o.camera);
    list_cameras(&scene);
    return EXIT_USAGE;
  }
  if (st != BALL_OK) {
    fprintf(stderr, "ballrender: camera %s: %s\n", o.camera, ball_strerror(st));
    return 1;
  }
  if (!prepare_dir(o.out_dir)) return 1;

  st = ball_replay_init(&replay, &scene, o.trail >= 0.0 ? o.trail : scene.render.trail,
                        o.markers >= 0.0 ? o.markers : scene.render.markers);
  if (st != BALL_OK) {
    fprintf(stderr, "ballrender: cannot start the scene: %s\n", ball_strerror(st));
    return 1;
  }
  st = ball_renderer_create(o.width, o.height, &renderer);
  if (st != BALL_OK) {
    fprintf(stderr, "ballrender: cannot make an OSMesa context of %dx%d: %s\n", o.width, o.height, ball_strerror(st));
    return 1;
  }
  for (i = 0; i < n_times; ++i) {
    ball_frame frame;
    const unsigned char *rgb;
    char path[4096];
    double px = 0.0, py = 0.0;
    st = ball_replay_frame(&replay, times[i], &frame);
    if (st == BALL_OK) st = ball_render_draw(renderer, &scene.model, &cam, &frame);
    if (st != BALL_OK) {
      fprintf(stderr, "ballrender: frame at t=%.3f: %s\n", times[i], ball_strerror(st));
      ball_renderer_destroy(renderer);
      return 1;
    }
    ball_render_pixels(renderer, &rgb, NULL, NULL);
    snprintf(path, sizeof path, "%s/t%08.3f.png", o.out_dir, times[i]);
    errno = 0;
    if (ball_png_write(path, rgb, o.width, o.height) != BALL_OK) {
      fprintf(stderr, "ballrender: %s: %s\n", path, errno ? strerror(errno) : "cannot write the PNG");
      ball_renderer_destroy(renderer);
      return 1;
    }
    if (ball_camera_project(&cam, o.width, o.height, frame.ball, &px, &py, NULL) != BALL_OK) px = py = NAN;
    printf("frame t=%.3f file=%s ball=%.17g,%.17g,%.17g pixel=%.3f,%.3f\n", times[i], path, frame.ball.x, frame.ball.y,
           frame.ball.z, px, py);
  }
  ball_renderer_destroy(renderer);
  if (fflush(stdout) != 0) return 1;
  return 0;
}
