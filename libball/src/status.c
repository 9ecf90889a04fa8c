/* Status codes and enum names. */
#include "internal.h"

const char *ball_strerror(ball_status status) {
  switch (status) {
    case BALL_OK: return "success";
    case BALL_EINVAL: return "invalid argument (NULL pointer or wrong kind)";
    case BALL_ENONFINITE: return "a value is NaN or infinite";
    case BALL_ERANGE: return "a value is outside its allowed range";
    case BALL_ENOTFOUND: return "no solution: the ball never gets there";
    case BALL_ESTALE: return "racket sample older than the newest kept, or track stale";
    case BALL_ENOSPACE: return "no room left";
    case BALL_EPARSE: return "scene file is not valid";
    case BALL_EIO: return "file cannot be read";
    case BALL_ENOMEM: return "out of memory";
    case BALL_EDUPLICATE: return "racket sample identical to one already kept: ignored";
    case BALL_ENOMATCH: return "no such match on this client (not followed, or no slot held)";
    case BALL_EAGAIN: return "not yet: the server has not said enough";
    case BALL_ENETWORK: return "the network refused";
    case BALL_ECLOSED: return "the client is closed";
    case BALL_STATUS_COUNT: break;
  }
  return "unknown status";
}

const char *ball_scheme_name(ball_scheme scheme) {
  static const char *const names[] = {"sampled", "exact"};
  return (unsigned)scheme < BALL_SCHEME_COUNT ? names[scheme] : "unknown";
}

const char *ball_detect_name(ball_detect detect) {
  static const char *const names[] = {"sphere", "disc", "swept"};
  return (unsigned)detect < BALL_DETECT_COUNT ? names[detect] : "unknown";
}

const char *ball_normal_mode_name(ball_normal_mode mode) {
  static const char *const names[] = {"real", "velocity"};
  return (unsigned)mode < BALL_NORMAL_COUNT ? names[mode] : "unknown";
}

const char *ball_response_name(ball_response response) {
  static const char *const names[] = {"racket", "autonomous", "mixed", "physical"};
  return (unsigned)response < BALL_RESPONSE_COUNT ? names[response] : "unknown";
}

const char *ball_level_name(ball_level level) {
  static const char *const names[] = {"custom", "easy", "mid", "advanced"};
  return (unsigned)level < BALL_LEVEL_COUNT ? names[level] : "unknown";
}

const char *ball_event_kind_name(ball_event_kind kind) {
  static const char *const names[] = {"floor", "net", "wall", "racket"};
  return (unsigned)kind < BALL_EVENT_KIND_COUNT ? names[kind] : "unknown";
}

const char *ball_effect_name(ball_effect effect) {
  switch (effect) {
    case BALL_EFFECT_DRAG: return "drag";
    case BALL_EFFECT_SPIN: return "spin";
    case BALL_EFFECT_FLOOR: return "floor";
    case BALL_EFFECT_NET: return "net";
    case BALL_EFFECT_WALLS: return "walls";
    case BALL_EFFECT_RACKETS: return "rackets";
    case BALL_EFFECT_SOUND: return "sound";
    case BALL_EFFECT_ALL: break;
  }
  return "unknown";
}
