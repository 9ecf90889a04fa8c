/* ballrender: snapshot frames of a libball scene as PNG files, headless
 * (OSMesa). The scene is played as ballsim plays it (ball_scene_run), so the
 * ball is drawn where libball puts it. With --compare the frames are checked
 * against golden PNGs (snapshot.h decides). See docs/render.md. */
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
#include "snapshot.h"

#define TOOL_NAME "ballrender"
#include "args.h"

#define MAX_FRAMES 10000
#define MAX_TIME 86400.0 /* s */
#define DEFAULT_WIDTH 640
#define DEFAULT_HEIGHT 480
/* --compare: libball's own goldens' tolerance (docs/render.md, "Tolerance"),
 * tests/render/cases.cmake holds them equal; no pixel over it by default */
#define DEFAULT_TOLERANCE 8
#define DEFAULT_MAX_PIXELS 0
#define MAX_MAX_PIXELS ((long)BALL_RENDER_MAX_SIZE * BALL_RENDER_MAX_SIZE)
#define PATH_SIZE 4096

typedef struct options {
  const char *scene_path;
  const char *times_text;  /* --times */
  double every;            /* --every, 0: not given */
  double duration;         /* --duration, 0: the scene's */
  const char *camera;
  int width, height;
  const char *out_dir;     /* NULL: frames not written (with --compare) */
  double trail, markers;   /* < 0: the scene's */
  const char *compare_dir; /* --compare: the goldens' folder; NULL: no comparison */
  int update;              /* --update: write the goldens instead */
  long tolerance;          /* levels of 255; < 0: not given */
  long max_pixels;         /* < 0: not given */
  const char *diff_arg;    /* --diff as given, NULL: not given */
  char diff_dir[PATH_SIZE]; /* where frames that fail go (snapshot_diff_dir) */
} options;

static void print_help(FILE *f) {
  fprintf(f,
          "usage: ballrender SCENE (--times T1,T2,... | --every S [--duration S])\n"
          "                  [--camera NAME] [--size WxH] [--trail S] [--markers S] --out DIR\n"
          "       ballrender SCENE (--times ... | --every ...) [--camera ...] [...]\n"
          "                  --compare GOLDEN_DIR [--tolerance N] [--max-pixels N]\n"
          "                  [--diff DIR] [--out DIR]\n"
          "       ballrender SCENE (--times ... | --every ...) [--camera ...] [...]\n"
          "                  --compare GOLDEN_DIR --update\n"
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
          "  --compare GOLDEN_DIR\n"
          "                   snapshot regression: compare each frame with its golden,\n"
          "                   GOLDEN_DIR/tSSSS.mmm.png (the name --out gives it); a frame\n"
          "                   that fails is written to the --diff folder with its diff\n"
          "                   image\n"
          "  --update         with --compare: write the frames into GOLDEN_DIR as the\n"
          "                   goldens (made if missing) instead of comparing\n"
          "  --tolerance N    with --compare: a pixel differs when one of its channels is\n"
          "                   more than N of 255 apart, [0, 255]; default %d (the\n"
          "                   tolerance of libball's own goldens)\n"
          "  --max-pixels N   with --compare: a frame differs when more than N pixels\n"
          "                   differ, [0, %ld]; default %d\n"
          "  --diff DIR       with --compare: folder for each frame that fails,\n"
          "                   tSSSS.mmm.png, and its diff image tSSSS.mmm.diff.png (the\n"
          "                   golden dimmed, differing pixels red); made when needed;\n"
          "                   default the --out DIR, else GOLDEN_DIR-diff\n"
          "  -h, --help       this text\n"
          "\n"
          "Output: one line per frame written to --out:\n"
          "  frame t=T file=PATH ball=X,Y,Z pixel=PX,PY\n"
          "(the ball centre in m, to the last bit, and where it is in the image in\n"
          "pixels, x right and y down from the top-left corner); with --compare one\n"
          "line per frame compared and a summary:\n"
          "  compare t=T golden=PATH result=same|differs|missing|size|unreadable\n"
          "          [golden_size=WxH size=WxH] [differing=N max_diff=M [first=X,Y]]\n"
          "          [diff=PATH] [actual=PATH]\n"
          "  summary: frames=N same=N differs=N missing=N size=N unreadable=N\n"
          "           tolerance=N max_pixels=N\n"
          "(differing: pixels over the tolerance; max_diff: the largest difference of\n"
          "a channel; first: the first differing pixel, row by row); with --update\n"
          "one line per golden written:\n"
          "  update t=T golden=PATH\n"
          "Exit status: 0 on success, 1 for a scene or runtime error (a scene error is\n"
          "FILE:LINE:COLUMN: FIELD: MESSAGE) or, with --compare, for a frame that is not\n"
          "the same as its golden (differs, missing, another size, unreadable), 2 for\n"
          "bad arguments.\n",
          DEFAULT_TOLERANCE, MAX_MAX_PIXELS, DEFAULT_MAX_PIXELS);
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

/* The options of --compare together; returns -1 on success, else the exit
 * status. */
static int check_compare_args(options *o) {
  const char *given = NULL; /* an option that goes with --compare alone */
  if (o->diff_arg) given = "--diff";
  if (o->max_pixels >= 0) given = "--max-pixels";
  if (o->tolerance >= 0) given = "--tolerance";
  if (!o->compare_dir) {
    if (o->update) return usage_error("--update goes with --compare GOLDEN_DIR");
    if (given) return usage_error("%s goes with --compare GOLDEN_DIR", given);
    if (!o->out_dir) return usage_error("give --out DIR or --compare GOLDEN_DIR");
    return -1;
  }
  if (o->update) {
    if (given || o->out_dir)
      return usage_error("%s does not go with --update (it writes the goldens into the --compare folder)",
                         given ? given : "--out");
    return -1;
  }
  if (o->tolerance < 0) o->tolerance = DEFAULT_TOLERANCE;
  if (o->max_pixels < 0) o->max_pixels = DEFAULT_MAX_PIXELS;
  if (!snapshot_diff_dir(o->diff_dir, sizeof o->diff_dir, o->compare_dir, o->out_dir, o->diff_arg)) {
    if (o->diff_arg || o->out_dir) return usage_error("--diff: the folder name is too long");
    return usage_error("--compare %s: no folder name to put \"-diff\" after for the frames that fail: give --diff DIR",
                       o->compare_dir);
  }
  return -1;
}

/* Returns -1 on success, else the exit status. */
static int parse_args(int argc, char **argv, options *o) {
  static const struct option longs[] = {
      {"times", required_argument, NULL, 't'},  {"every", required_argument, NULL, 'e'},
      {"duration", required_argument, NULL, 'd'}, {"camera", required_argument, NULL, 'c'},
      {"size", required_argument, NULL, 's'},   {"out", required_argument, NULL, 'o'},
      {"trail", required_argument, NULL, 'r'},  {"markers", required_argument, NULL, 'm'},
      {"compare", required_argument, NULL, 'C'}, {"update", no_argument, NULL, 'U'},
      {"tolerance", required_argument, NULL, 'T'}, {"max-pixels", required_argument, NULL, 'M'},
      {"diff", required_argument, NULL, 'D'},   {"help", no_argument, NULL, 'h'},
      {NULL, 0, NULL, 0}};
  int c;
  memset(o, 0, sizeof *o);
  o->camera = "side";
  o->width = DEFAULT_WIDTH;
  o->height = DEFAULT_HEIGHT;
  o->trail = o->markers = -1.0;
  o->tolerance = o->max_pixels = -1;
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
      case 'C':
      case 'D':
        if (!*v) return usage_error("--%s: empty folder name", c == 'o' ? "out" : c == 'C' ? "compare" : "diff");
        *(c == 'o' ? &o->out_dir : c == 'C' ? &o->compare_dir : &o->diff_arg) = v;
        break;
      case 'U': o->update = 1; break;
      case 'T':
        if (!parse_integer(v, 0, 255, &o->tolerance))
          return usage_error("--tolerance: expected a whole number in [0, 255], got \"%s\"", v);
        break;
      case 'M':
        if (!parse_integer(v, 0, MAX_MAX_PIXELS, &o->max_pixels))
          return usage_error("--max-pixels: expected a whole number in [0, %ld], got \"%s\"", MAX_MAX_PIXELS, v);
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
  return check_compare_args(o);
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

/* The folder of option exists (made if missing) and takes files. */
static int prepare_dir(const char *option, const char *dir) {
  struct stat sb;
  if (stat(dir, &sb) != 0) {
    if (errno != ENOENT || mkdir(dir, 0777) != 0) {
      fprintf(stderr, "ballrender: %s %s: %s\n", option, dir, strerror(errno));
      return 0;
    }
  } else if (!S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "ballrender: %s %s: %s\n", option, dir, strerror(ENOTDIR));
    return 0;
  }
  if (access(dir, W_OK | X_OK) != 0) {
    fprintf(stderr, "ballrender: %s %s: %s\n", option, dir, strerror(errno));
    return 0;
  }
  return 1;
}

/* DIR/tSSSS.mmm.png (suffix NULL) or another name of the frame at t. */
static int frame_path(char *path, const char *dir, double t, const char *suffix) {
  if (snapshot_file_name(path, PATH_SIZE, dir, t, suffix)) return 1;
  fprintf(stderr, "ballrender: %s: the file names in it are too long\n", dir);
  return 0;
}

static int write_png(const char *path, const unsigned char *rgb, int width, int height) {
  errno = 0;
  if (ball_png_write(path, rgb, width, height) == BALL_OK) return 1;
  fprintf(stderr, "ballrender: %s: %s\n", path, errno ? strerror(errno) : "cannot write the PNG");
  return 0;
}

/* What --compare found over the frames. */
typedef struct compare_tally {
  int frames;
  int by_result[SNAPSHOT_RESULT_COUNT];
  int diff_dir_made;       /* the --diff folder is there */
  unsigned char *diff_rgb; /* width * height * 3 */
} compare_tally;

/* --compare for one frame: the line, and a frame that fails written to the
 * diff folder with its diff image. Returns 0 after a runtime error. */
static int compare_frame(const options *o, double t, const unsigned char *rgb, compare_tally *k) {
  char golden[PATH_SIZE], actual[PATH_SIZE], diff[PATH_SIZE];
  snapshot_check check;
  ball_status st;
  int fails;
  if (!frame_path(golden, o->compare_dir, t, NULL)) return 0;
  st = snapshot_compare(golden, rgb, o->width, o->height, (int)o->tolerance, o->max_pixels, &check, k->diff_rgb);
  if (st != BALL_OK) {
    fprintf(stderr, "ballrender: frame at t=%.3f against %s: %s\n", t, golden, ball_strerror(st));
    return 0;
  }
  k->frames++;
  k->by_result[check.result]++;
  if (check.result == SNAPSHOT_UNREADABLE)
    fprintf(stderr, "ballrender: %s: %s\n", golden, snapshot_read_error(check.read_status));
  fails = check.result != SNAPSHOT_SAME;
  if (fails) {
    if (!k->diff_dir_made && !prepare_dir("--diff", o->diff_dir)) return 0;
    k->diff_dir_made = 1;
    /* the frame beside its diff image, unless --out wrote it there already */
    if (!frame_path(actual, o->diff_dir, t, NULL) || !frame_path(diff, o->diff_dir, t, ".diff.png")) return 0;
    if (!(o->out_dir && strcmp(o->out_dir, o->diff_dir) == 0) && !write_png(actual, rgb, o->width, o->height))
      return 0;
    if (check.result == SNAPSHOT_DIFFERS && !write_png(diff, k->diff_rgb, o->width, o->height)) return 0;
  }
  snapshot_print(stdout, t, golden, &check, o->width, o->height,
                 fails && check.result == SNAPSHOT_DIFFERS ? diff : NULL, fails ? actual : NULL);
  return 1;
}

/* The summary line and the hints; returns the exit status. */
static int compare_summary(const options *o, const compare_tally *k) {
  int failed = k->frames - k->by_result[SNAPSHOT_SAME];
  printf("summary: frames=%d same=%d differs=%d missing=%d size=%d unreadable=%d tolerance=%ld max_pixels=%ld\n",
         k->frames, k->by_result[SNAPSHOT_SAME], k->by_result[SNAPSHOT_DIFFERS], k->by_result[SNAPSHOT_MISSING],
         k->by_result[SNAPSHOT_SIZE], k->by_result[SNAPSHOT_UNREADABLE], o->tolerance, o->max_pixels);
  if (k->by_result[SNAPSHOT_MISSING] > 0)
    fprintf(stderr, "ballrender: no golden in %s for %d of %d frames: --update writes them\n", o->compare_dir,
            k->by_result[SNAPSHOT_MISSING], k->frames);
  if (failed > 0)
    fprintf(stderr, "ballrender: %d of %d frames fail; they are in %s\n", failed, k->frames, o->diff_dir);
  return failed > 0 ? 1 : 0;
}

static void list_cameras(const ball_scene *scene) {
  int i;
  fprintf(stderr, "valid cameras:");
  for (i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i) fprintf(stderr, " %s", ball_camera_preset_name((ball_camera_preset)i));
  for (i = 0; i < scene->render.n_cameras; ++i) fprintf(stderr, " %s", scene->render.cameras[i].name);
  fprintf(stderr, "\n");
}

/* --out: the frame and its line. */
static int out_frame(const options *o, const ball_camera *cam, double t, const ball_frame *frame,
                     const unsigned char *rgb) {
  char path[PATH_SIZE];
  double px = 0.0, py = 0.0;
  if (!frame_path(path, o->out_dir, t, NULL) || !write_png(path, rgb, o->width, o->height)) return 0;
  if (ball_camera_project(cam, o->width, o->height, frame->ball, &px, &py, NULL) != BALL_OK) px = py = NAN;
  printf("frame t=%.3f file=%s ball=%.17g,%.17g,%.17g pixel=%.3f,%.3f\n", t, path, frame->ball.x, frame->ball.y,
         frame->ball.z, px, py);
  return 1;
}

/* --update: the golden and its line. */
static int update_frame(const options *o, double t, const unsigned char *rgb) {
  char path[PATH_SIZE];
  if (!frame_path(path, o->compare_dir, t, NULL) || !write_png(path, rgb, o->width, o->height)) return 0;
  printf("update t=%.3f golden=%s\n", t, path);
  return 1;
}

int main(int argc, char **argv) {
  options o;
  static ball_scene scene;
  static ball_replay replay; /* about 200 kB: off the stack */
  static double times[MAX_FRAMES];
  ball_camera cam;
  ball_renderer *renderer = NULL;
  compare_tally tally;
  ball_status st;
  int rc, n_times, i, ok, comparing;

  memset(&tally, 0, sizeof tally);
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
  if (o.out_dir && !prepare_dir("--out", o.out_dir)) return 1;
  if (o.update && !prepare_dir("--compare", o.compare_dir)) return 1;

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
  comparing = o.compare_dir && !o.update;
  if (comparing) {
    tally.diff_rgb = (unsigned char *)malloc((size_t)o.width * o.height * 3);
    if (!tally.diff_rgb) {
      fprintf(stderr, "ballrender: %s\n", ball_strerror(BALL_ENOMEM));
      ball_renderer_destroy(renderer);
      return 1;
    }
  }
  for (i = 0; i < n_times && rc < 0; ++i) {
    ball_frame frame;
    const unsigned char *rgb;
    st = ball_replay_frame(&replay, times[i], &frame);
    if (st == BALL_OK) st = ball_render_draw(renderer, &scene.model, &cam, &frame);
    if (st != BALL_OK) {
      fprintf(stderr, "ballrender: frame at t=%.3f: %s\n", times[i], ball_strerror(st));
      rc = 1;
      break;
    }
    ball_render_pixels(renderer, &rgb, NULL, NULL);
    ok = !o.out_dir || out_frame(&o, &cam, times[i], &frame, rgb);
    if (ok && o.update) ok = update_frame(&o, times[i], rgb);
    else if (ok && comparing) ok = compare_frame(&o, times[i], rgb, &tally);
    if (!ok) rc = 1;
  }
  ball_renderer_destroy(renderer);
  free(tally.diff_rgb);
  if (rc < 0) rc = comparing ? compare_summary(&o, &tally) : 0;
  if (fflush(stdout) != 0) return 1;
  return rc;
}
