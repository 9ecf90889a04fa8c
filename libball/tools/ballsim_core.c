/* ballsim's core (ballsim_core.h): arguments, the run, the output lines.
 * See docs/scenes.md, "ballsim". */
#define _POSIX_C_SOURCE 200809L

#include "ballsim_core.h"

#include <errno.h>
#include <getopt.h>
#include <time.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/scene.h"
#include "ball/vec3.h"

#define TOOL_NAME "ballsim"
#include "args.h"

#define MAX_FRAMES 1000000000.0
#define EVENT_CAP (BALL_MAX_CONTACTS + BALL_MAX_RACKETS + 8)

static void print_help(FILE *f) {
  fprintf(f,
          "usage: ballsim [SCENE] [--fps N] [--duration S] [--scheme sampled|exact]\n"
          "               [--out FILE] [--format csv|jsonl]\n"
          "       ballsim --keys\n"
          "       ballsim --help\n"
          "\n"
          "Runs a libball scene headless: steps the ball at the scene's frame rate,\n"
          "prints every collision event as one line and a summary at the end.\n"
          "Scripted rackets (rackets[i].script) send their samples as the scene's\n"
          "network conditions deliver them; before each step every sample that has\n"
          "arrived by the end of the step goes to ball_racket_push.\n"
          "\n"
          "  SCENE               a YAML scene file (docs/scenes.md); without it the\n"
          "                      built-in tennis serve (the same as libball/scenes/tennis.yaml)\n"
          "  --fps N             frames per second, N > 0; overrides the scene's time.frame_time\n"
          "  --duration S        sim seconds to run, S > 0; overrides the scene's duration.\n"
          "                      The run takes ceil(S / dt) frames of dt = frame_time * time_base\n"
          "                      sim seconds each.\n"
          "  --scheme MODE       static obstacle detection: sampled (the paper's per-frame\n"
          "                      tests) or exact (contact times in closed form)\n"
          "  --out FILE          write the trajectory, one record per frame including t = 0:\n"
          "                      t,px,py,pz,vx,vy,vz,sx,sy,sz (s, m, m/s, spin m/s)\n"
          "  --format FMT        csv (a header row, then one row per frame) or jsonl (one JSON\n"
          "                      object per line with the same names); default: from FILE's\n"
          "                      extension, .csv or .jsonl\n"
          "  --keys              print the model keys of a scene file (the field table of\n"
          "                      libball) as the Markdown table of docs/scenes.md, and stop\n"
          "  -h, --help          this text\n"
          "\n"
          "Output lines:\n"
          "  scene: NAME (FILE) scheme=... fps=... dt=... frames=... effects=...\n"
          "  event t=T kind=floor|net|wall|racket index=I point=X,Y,Z v_in=X,Y,Z\n"
          "        v_out=X,Y,Z spin_out=X,Y,Z speed_in=S speed_out=S sound=0|1\n"
          "  summary: frames=N time=T events=N floor=N net=N wall=N racket=N sounds=N\n"
          "  samples: arrived=N accepted=N duplicate=N stale=N invalid=N\n"
          "  final: position=X,Y,Z velocity=X,Y,Z spin=X,Y,Z grounded=0|1\n"
          "  warnings: event_overflow=N contact_limit=N stale_racket=N\n"
          "\n"
          "Text in these lines (the scene's name, the file name) is printed with control\n"
          "characters escaped (\\n, \\t, \\xNN), so a scene cannot fake a line. Numbers\n"
          "print as %%.6f (speeds %%.4f) between 1e-3 and 1e9, and as %%.17g beyond.\n"
          "On a terminal a long run shows its progress on stderr; Ctrl-C stops it\n"
          "cleanly after the frame in hand (the summary says interrupted=1, exit 130).\n"
          "\n"
          "Exit status: 0 on success, 1 for a scene or runtime error (printed as\n"
          "FILE:LINE:COLUMN: FIELD: MESSAGE), 2 for bad arguments, 130 interrupted.\n");
}

/* A finite number > 0, the whole text consumed. */
static int parse_positive(const char *text, double *out) {
  double v;
  if (!parse_number(text, &v) || !(v > 0.0)) return 0;
  *out = v;
  return 1;
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* Returns -1 on success, else the exit status. */
int ballsim_parse_args(int argc, char **argv, ballsim_options *o, FILE *out, FILE *err) {
  static const struct option longs[] = {
      {"fps", required_argument, NULL, 'f'},    {"duration", required_argument, NULL, 'd'},
      {"scheme", required_argument, NULL, 's'}, {"out", required_argument, NULL, 'o'},
      {"format", required_argument, NULL, 'F'}, {"keys", no_argument, NULL, 'k'},
      {"help", no_argument, NULL, 'h'},         {NULL, 0, NULL, 0}};
  int c;
  memset(o, 0, sizeof *o);
  o->scheme = -1;
  opterr = 0;
#ifdef __GLIBC__
  optind = 0; /* glibc: a full restart of the scan, for a second call */
#else
  optind = 1;
#endif
  while ((c = getopt_long(argc, argv, ":h", longs, NULL)) != -1) {
    const char *value = optarg;
    switch (c) {
      case 'h': print_help(out); return 0;
      case 'k': o->keys = 1; break;
      case 'f':
        if (!parse_positive(value, &o->fps)) return tool_usage_error(err, "--fps: expected a number > 0, got \"%s\"", value);
        break;
      case 'd':
        if (!parse_positive(value, &o->duration))
          return tool_usage_error(err, "--duration: expected a number of seconds > 0, got \"%s\"", value);
        break;
      case 's': {
        int sc;
        for (sc = 0; sc < BALL_SCHEME_COUNT; ++sc)
          if (strcmp(value, ball_scheme_name((ball_scheme)sc)) == 0) break;
        if (sc == BALL_SCHEME_COUNT) return tool_usage_error(err, "--scheme: expected sampled or exact, got \"%s\"", value);
        o->scheme = sc;
        break;
      }
      case 'o':
        if (!*value) return tool_usage_error(err, "--out: empty file name");
        o->out_path = value;
        break;
      case 'F':
        if (strcmp(value, "csv") == 0) o->format = BALLSIM_FORMAT_CSV;
        else if (strcmp(value, "jsonl") == 0) o->format = BALLSIM_FORMAT_JSONL;
        else return tool_usage_error(err, "--format: expected csv or jsonl, got \"%s\"", value);
        break;
      case ':': return tool_usage_error(err, "%s needs a value", argv[optind - 1]);
      default: {
        /* the option as given, without a value glued to it with = */
        const char *a = argv[optind - 1];
        size_t n = strcspn(a, "=");
        return tool_usage_error(err, "unknown option %.*s", (int)n, a);
      }
    }
  }
  if (optind < argc) o->scene_path = argv[optind++];
  if (optind < argc) return tool_usage_error(err, "more than one scene given: %s and %s", o->scene_path, argv[optind]);
  if (o->format != BALLSIM_FORMAT_NONE && !o->out_path) return tool_usage_error(err, "--format needs --out FILE");
  if (o->out_path && o->format == BALLSIM_FORMAT_NONE) {
    if (ends_with(o->out_path, ".csv")) o->format = BALLSIM_FORMAT_CSV;
    else if (ends_with(o->out_path, ".jsonl")) o->format = BALLSIM_FORMAT_JSONL;
    else return tool_usage_error(err, "--out %s: cannot tell the format from the name; add --format csv|jsonl", o->out_path);
  }
  return -1;
}

/* ---- text output ---- */

void ballsim_put_text(FILE *f, const char *s) {
  for (; *s; ++s) {
    unsigned char c = (unsigned char)*s;
    if (c == '\\') fputs("\\\\", f);
    else if (c == '\n') fputs("\\n", f);
    else if (c == '\t') fputs("\\t", f);
    else if (c == '\r') fputs("\\r", f);
    else if (c < 0x20 || c == 0x7f) fprintf(f, "\\x%02x", c);
    else fputc(c, f);
  }
}

void ballsim_put_num(FILE *f, double v, int digits) {
  double a = fabs(v);
  if (v == 0.0 || (a >= 1e-3 && a < 1e9)) fprintf(f, "%.*f", digits, v);
  else fprintf(f, "%.17g", v);
}


/* ---- the key table (docs/scenes.md) ---- */

static const char *type_words(const ball_field *f, char *buf, size_t size) {
  int i;
  size_t used = 0;
  switch (f->type) {
    case BALL_FIELD_REAL: return "number";
    case BALL_FIELD_INT: return "integer";
    case BALL_FIELD_BOOL: return "boolean";
    case BALL_FIELD_AXIS: return "`x` or `z`";
    case BALL_FIELD_EFFECTS: return "list of names";
    case BALL_FIELD_VEC3: return "vector";
    case BALL_FIELD_PLANE: return "mapping or `none`";
    case BALL_FIELD_PLANES:
    case BALL_FIELD_RACKETS: return "list of mappings";
    case BALL_FIELD_ENUM:
      buf[0] = '\0';
      for (i = 0; i <= (int)f->hi && used < size; i++) {
        int w = snprintf(buf + used, size - used, "%s`%s`", i ? ", " : "", f->enum_name(i));
        if (w < 0) break;
        used += (size_t)w;
      }
      return buf;
    default: return "";
  }
}

static void put_default(FILE *out, const ball_field *f) {
  unsigned bit;
  int first = 1;
  switch (f->type) {
    case BALL_FIELD_REAL: fprintf(out, "%.10g", f->def[0]); break;
    case BALL_FIELD_INT: fprintf(out, "%d", (int)f->def[0]); break;
    case BALL_FIELD_BOOL: fprintf(out, "`%s`", f->def[0] != 0.0 ? "true" : "false"); break;
    case BALL_FIELD_ENUM: fprintf(out, "`%s`", f->enum_name((int)f->def[0])); break;
    case BALL_FIELD_AXIS: fprintf(out, "`%s`", f->def[0] == 0.0 ? "x" : "z"); break;
    case BALL_FIELD_VEC3: fprintf(out, "[%.10g, %.10g, %.10g]", f->def[0], f->def[1], f->def[2]); break;
    case BALL_FIELD_EFFECTS:
      fprintf(out, "`[");
      for (bit = 1u; bit & BALL_EFFECT_ALL; bit <<= 1)
        if ((unsigned)f->def[0] & bit) {
          fprintf(out, "%s%s", first ? "" : ", ", ball_effect_name((ball_effect)bit));
          first = 0;
        }
      fprintf(out, "]`");
      break;
    default: break;
  }
}

static void key_row(FILE *out, const char *prefix, const ball_field *f, const char *def_override) {
  char types[160];
  fprintf(out, "| `%s%s` | %s | %s | ", prefix, f->key, type_words(f, types, sizeof types), f->unit);
  if (def_override) fprintf(out, "%s", def_override);
  else put_default(out, f);
  fprintf(out, " | %s%s%s", f->range, *f->range ? "; " : "", f->doc);
  if (*f->equation) fprintf(out, " (%s)", f->equation);
  fprintf(out, " |\n");
}

/* The model's keys as docs/scenes.md lists them: every field of the field
 * table under its scene key. */
int ballsim_print_keys(FILE *out) {
  int n, np, nr, i, j;
  const ball_field *f = ball_model_fields(&n);
  const ball_field *pf = ball_plane_fields(&np);
  const ball_field *rf = ball_racket_fields(&nr);
  fprintf(out, "| key | type | unit | default | range and meaning |\n|---|---|---|---|---|\n");
  for (i = 0; i < n; i++) {
    if (f[i].type == BALL_FIELD_INT && (strcmp(f[i].key, "walls") == 0 || strcmp(f[i].key, "rackets") == 0))
      continue; /* the counts are the lists' lengths */
    if (f[i].type == BALL_FIELD_BOOL && strcmp(f[i].key, "net") == 0) continue; /* `net: none` */
    key_row(out, "", &f[i], f[i].type == BALL_FIELD_PLANES || f[i].type == BALL_FIELD_RACKETS ? "`[]`" :
                      f[i].type == BALL_FIELD_PLANE ? "the court's net" : NULL);
    if (f[i].type == BALL_FIELD_PLANE)
      for (j = 0; j < np; j++) key_row(out, "net.", &pf[j], NULL);
    if (f[i].type == BALL_FIELD_PLANES)
      for (j = 0; j < np; j++)
        key_row(out, "walls[i].", &pf[j],
                strcmp(pf[j].key, "bottom") == 0 ? "`floor.level`" :
                strcmp(pf[j].key, "damping") == 0 ? "the default net's" : "required");
    if (f[i].type == BALL_FIELD_RACKETS)
      for (j = 0; j < nr; j++) key_row(out, "rackets[i].", &rf[j], NULL);
  }
  return fflush(out) == 0 ? 0 : 1;
}

/* ---- the run ---- */

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}


static void write_record(FILE *f, ballsim_format fmt, double t, const ball_state *s) {
  if (fmt == BALLSIM_FORMAT_CSV) {
    fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, s->position.x, s->position.y,
            s->position.z, s->velocity.x, s->velocity.y, s->velocity.z, s->spin.x, s->spin.y, s->spin.z);
  } else {
    fprintf(f,
            "{\"t\":%.17g,\"px\":%.17g,\"py\":%.17g,\"pz\":%.17g,\"vx\":%.17g,\"vy\":%.17g,\"vz\":%.17g,"
            "\"sx\":%.17g,\"sy\":%.17g,\"sz\":%.17g}\n",
            t, s->position.x, s->position.y, s->position.z, s->velocity.x, s->velocity.y, s->velocity.z, s->spin.x,
            s->spin.y, s->spin.z);
  }
}

static void print_effects(FILE *out, unsigned effects) {
  unsigned bit;
  int first = 1;
  for (bit = 1u; bit & BALL_EFFECT_ALL; bit <<= 1) {
    if (effects & bit) {
      fprintf(out, "%s%s", first ? "" : ",", ball_effect_name((ball_effect)bit));
      first = 0;
    }
  }
  if (first) fprintf(out, "none");
}

static int runtime_error(FILE *err, const char *what, ball_status st) {
  fprintf(err, "ballsim: %s: %s\n", what, ball_strerror(st));
  return BALLSIM_EXIT_ERROR;
}


static void put_vec(FILE *f, ball_vec3 v, int digits) {
  ballsim_put_num(f, v.x, digits);
  fputc(',', f);
  ballsim_put_num(f, v.y, digits);
  fputc(',', f);
  ballsim_put_num(f, v.z, digits);
}

static void put_event(FILE *out, const ball_event *e) {
  fprintf(out, "event t=");
  ballsim_put_num(out, e->time, 6);
  fprintf(out, " kind=%s index=%d point=", ball_event_kind_name(e->kind), e->index);
  put_vec(out, e->point, 6);
  fprintf(out, " v_in=");
  put_vec(out, e->velocity_in, 4);
  fprintf(out, " v_out=");
  put_vec(out, e->velocity_out, 4);
  fprintf(out, " spin_out=");
  put_vec(out, e->spin_out, 4);
  fprintf(out, " speed_in=");
  ballsim_put_num(out, ball_v3_norm(e->velocity_in), 4);
  fprintf(out, " speed_out=");
  ballsim_put_num(out, ball_v3_norm(e->velocity_out), 4);
  fprintf(out, " sound=%d\n", e->sound ? 1 : 0);
}

/* What a run counts, for the summary. */
typedef struct tally {
  unsigned long frames;                        /* frames stepped */
  unsigned long events, sounds;
  unsigned long kind[BALL_EVENT_KIND_COUNT];
} tally;

static void put_summary(FILE *out, const ball_scene_run *run, const tally *t, const ball_state *state, int stopped) {
  const ball_sim *sim = &run->sim;
  fprintf(out, "summary: frames=%lu time=", t->frames);
  ballsim_put_num(out, sim->time, 6);
  fprintf(out, " events=%lu floor=%lu net=%lu wall=%lu racket=%lu sounds=%lu%s\n", t->events,
          t->kind[BALL_EVENT_FLOOR], t->kind[BALL_EVENT_NET], t->kind[BALL_EVENT_WALL], t->kind[BALL_EVENT_RACKET],
          t->sounds, stopped ? " interrupted=1" : "");
  fprintf(out, "samples: arrived=%lu accepted=%lu duplicate=%lu stale=%lu invalid=%lu\n", run->arrived,
          run->accepted, run->duplicate, run->stale, run->invalid);
  fprintf(out, "final: position=");
  put_vec(out, state->position, 6);
  fprintf(out, " velocity=");
  put_vec(out, state->velocity, 6);
  fprintf(out, " spin=");
  put_vec(out, state->spin, 6);
  fprintf(out, " grounded=%d\n", sim->seg.grounded);
  fprintf(out, "warnings: event_overflow=%lu contact_limit=%lu stale_racket=%lu\n",
          sim->warnings[BALL_WARN_EVENT_OVERFLOW], sim->warnings[BALL_WARN_CONTACT_LIMIT],
          sim->warnings[BALL_WARN_STALE_RACKET]);
}

/* The scene as the options change it, checked; the frames to run. */
static int prepare(const ballsim_options *o, FILE *err, ball_scene *scene, unsigned long *frames) {
  const char *field = NULL;
  double dt, duration, frames_d;
  ball_status st;
  if (o->scene_path) {
    if (!load_scene_to(err, o->scene_path, scene)) return BALLSIM_EXIT_ERROR;
  } else {
    ball_scene_default(scene);
  }
  if (o->fps > 0.0) scene->frame_time = 1.0 / o->fps;
  if (o->scheme >= 0) scene->model.scheme = (ball_scheme)o->scheme;
  duration = o->duration > 0.0 ? o->duration : scene->duration;
  st = ball_model_check(&scene->model, &field);
  if (st != BALL_OK) {
    fprintf(err, "ballsim: %s: %s: %s\n", o->scene_path ? o->scene_path : "built-in scene", field ? field : "model",
            ball_strerror(st));
    return BALLSIM_EXIT_ERROR;
  }
  dt = scene->frame_time * scene->time_base;
  frames_d = ceil(duration / dt * (1.0 - 1e-12));
  if (!(dt > 0.0) || !isfinite(dt) || !(frames_d <= MAX_FRAMES)) {
    fprintf(err, "ballsim: %g s at a step of %g s is more than %.0f frames\n", duration, dt, MAX_FRAMES);
    return BALLSIM_EXIT_ERROR;
  }
  *frames = (unsigned long)frames_d;
  return -1;
}

/* The trajectory file: one record a frame (and t = 0). */
static int record(FILE *traj, ballsim_format fmt, const ball_sim *sim, FILE *err) {
  ball_state state;
  ball_status st = ball_sim_state(sim, &state);
  if (st != BALL_OK) return runtime_error(err, "cannot read the state", st);
  write_record(traj, fmt, sim->time, &state);
  return -1;
}

int ballsim_run(const ballsim_options *o, FILE *out, FILE *err, const volatile sig_atomic_t *stop) {
  ball_scene scene;
  static ball_scene_run run; /* about 60 kB: kept off the stack */
  const ball_sim *sim = &run.sim;
  ball_state state;
  ball_event events[EVENT_CAP];
  tally t;
  FILE *traj = NULL;
  ball_status st;
  unsigned long frames, k;
  int rc, i, stopped = 0, progress;
  double last_progress;

  if ((rc = prepare(o, err, &scene, &frames)) >= 0) return rc;
  st = ball_scene_run_init(&run, &scene);
  if (st != BALL_OK) return runtime_error(err, "cannot start the sim", st);
  if (o->out_path) {
    traj = fopen(o->out_path, "w");
    if (!traj) {
      fprintf(err, "ballsim: %s: %s\n", o->out_path, strerror(errno));
      return BALLSIM_EXIT_ERROR;
    }
    if (o->format == BALLSIM_FORMAT_CSV) fprintf(traj, "t,px,py,pz,vx,vy,vz,sx,sy,sz\n");
    if ((rc = record(traj, o->format, sim, err)) >= 0) goto done;
  }

  fprintf(out, "scene: ");
  ballsim_put_text(out, scene.name[0] ? scene.name : "unnamed");
  fprintf(out, " (");
  ballsim_put_text(out, o->scene_path ? o->scene_path : "built-in");
  fprintf(out, ") scheme=%s fps=%.6g dt=%.9g frames=%lu effects=", ball_scheme_name(scene.model.scheme),
          1.0 / scene.frame_time, run.dt, frames);
  print_effects(out, scene.model.effects);
  fprintf(out, "\n");
  progress = o->progress && frames > 100000;
  last_progress = wall_now();

  memset(&t, 0, sizeof t);
  for (k = 0; k < frames && !(stopped = stop && *stop); ++k) {
    int n = 0;
    /* the racket samples that have arrived by the end of the step, then the step */
    st = ball_scene_run_step(&run, events, EVENT_CAP, &n);
    if (st != BALL_OK) {
      fprintf(err, "ballsim: step %lu at t=%.9g: %s\n", k + 1, sim->time, ball_strerror(st));
      rc = BALLSIM_EXIT_ERROR;
      goto done;
    }
    for (i = 0; i < n; ++i) {
      put_event(out, &events[i]);
      if ((unsigned)events[i].kind < BALL_EVENT_KIND_COUNT) t.kind[events[i].kind]++;
      t.events++;
      if (events[i].sound) t.sounds++;
    }
    if (traj && (rc = record(traj, o->format, sim, err)) >= 0) goto done;
    if (progress && (k & 1023) == 0 && wall_now() - last_progress >= 1.0) {
      last_progress = wall_now();
      fprintf(err, "\rballsim: frame %lu of %lu (%.1f %%), sim time %.3f s ", k + 1, frames,
              100.0 * (double)(k + 1) / (double)frames, sim->time);
    }
  }
  if (progress) fprintf(err, "\n");
  t.frames = k; /* the frames run (fewer when stopped) */
  rc = -1;

done:
  if (traj) {
    int bad = ferror(traj);
    if ((fclose(traj) != 0 || bad) && rc < 0) {
      fprintf(err, "ballsim: %s: write failed\n", o->out_path);
      return BALLSIM_EXIT_ERROR;
    }
  }
  if (rc >= 0) return rc;
  st = ball_sim_state(sim, &state);
  if (st != BALL_OK) return runtime_error(err, "cannot read the state", st);
  put_summary(out, &run, &t, &state, stopped);
  if (fflush(out) != 0 || ferror(out)) return BALLSIM_EXIT_ERROR;
  return stopped ? BALLSIM_EXIT_INTERRUPTED : BALLSIM_EXIT_OK;
}
