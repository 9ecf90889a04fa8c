// The match's model on the wire (docs/protocol.md, "The match's model"):
// every field of libball's ball_model, as its field table lists them, goes
// into a MatchModel sample's bytes and comes back the same; an enum out of
// range in the bytes comes back as one ball_model_check refuses; a reader
// uses a MatchModel only with a checked model whose hash is its own and the
// MatchInfo's. Through server/dds's serialized and deserialized: the bytes a
// writer sends and a reader takes, no DDS header here.
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "check.hpp"
#include "records.h"
#include "testing/raw.h"
#include "trust.h"

using namespace ballsrv;

namespace {

// Every field of a struct described by a field table, filled with random
// values of its type (in range or not: the wire carries what it is given).
void fill(std::mt19937_64 &rng, void *base, const ball_field *f, int n) {
  std::uniform_real_distribution<double> real(-1e3, 1e3);
  for (int i = 0; i < n; ++i, ++f) {
    char *p = static_cast<char *>(base) + f->offset;
    auto between = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    switch (f->type) {
      case BALL_FIELD_REAL: *reinterpret_cast<double *>(p) = real(rng); break;
      case BALL_FIELD_INT: *reinterpret_cast<int *>(p) = between(static_cast<int>(f->lo), static_cast<int>(f->hi)); break;
      case BALL_FIELD_BOOL: *reinterpret_cast<int *>(p) = between(0, 1); break;
      case BALL_FIELD_ENUM: *reinterpret_cast<int *>(p) = between(0, static_cast<int>(f->hi)); break;
      case BALL_FIELD_AXIS: *reinterpret_cast<int *>(p) = between(0, 1) * 2; break;
      case BALL_FIELD_EFFECTS: *reinterpret_cast<unsigned *>(p) = static_cast<unsigned>(between(0, BALL_EFFECT_ALL)); break;
      case BALL_FIELD_VEC3: *reinterpret_cast<ball_vec3 *>(p) = ball_vec3{real(rng), real(rng), real(rng)}; break;
      case BALL_FIELD_PLANE: {
        int k = 0;
        const ball_field *pf = ball_plane_fields(&k);
        fill(rng, p, pf, k);
        break;
      }
      case BALL_FIELD_PLANES: {
        int k = 0;
        const ball_field *pf = ball_plane_fields(&k);
        for (int w = 0; w < BALL_MAX_WALLS; ++w) fill(rng, reinterpret_cast<ball_plane *>(p) + w, pf, k);
        break;
      }
      case BALL_FIELD_RACKETS: {
        int k = 0;
        const ball_field *rf = ball_racket_fields(&k);
        for (int r = 0; r < BALL_MAX_RACKETS; ++r) fill(rng, reinterpret_cast<ball_racket_def *>(p) + r, rf, k);
        break;
      }
      case BALL_FIELD_TYPE_COUNT: break;
    }
  }
}

// The first field (by its table) where a and b differ, or "" when none.
std::string differs(const void *a, const void *b, const ball_field *f, int n, const std::string &prefix = "") {
  for (int i = 0; i < n; ++i, ++f) {
    const char *pa = static_cast<const char *>(a) + f->offset;
    const char *pb = static_cast<const char *>(b) + f->offset;
    std::string name = prefix + f->name;
    size_t size = 0;
    switch (f->type) {
      case BALL_FIELD_REAL: size = sizeof(double); break;
      case BALL_FIELD_INT:
      case BALL_FIELD_BOOL:
      case BALL_FIELD_ENUM:
      case BALL_FIELD_AXIS: size = sizeof(int); break;
      case BALL_FIELD_EFFECTS: size = sizeof(unsigned); break;
      case BALL_FIELD_VEC3: size = sizeof(ball_vec3); break;
      case BALL_FIELD_PLANE: {
        int k = 0;
        const ball_field *pf = ball_plane_fields(&k);
        std::string d = differs(pa, pb, pf, k, name + ".");
        if (!d.empty()) return d;
        break;
      }
      case BALL_FIELD_PLANES:
      case BALL_FIELD_RACKETS: {
        int k = 0;
        bool walls = f->type == BALL_FIELD_PLANES;
        const ball_field *sf = walls ? ball_plane_fields(&k) : ball_racket_fields(&k);
        size_t stride = walls ? sizeof(ball_plane) : sizeof(ball_racket_def);
        for (int e = 0; e < (walls ? BALL_MAX_WALLS : BALL_MAX_RACKETS); ++e) {
          std::string d = differs(pa + e * stride, pb + e * stride, sf, k, name + "[" + std::to_string(e) + "].");
          if (!d.empty()) return d;
        }
        break;
      }
      case BALL_FIELD_TYPE_COUNT: break;
    }
    if (size && std::memcmp(pa, pb, size) != 0) return name;
  }
  return "";
}

// A real inside a field's bounds (a text or flag field is left as it is),
// or, with `outside`, one beyond an end that is finite (false: none is).
bool draw_setting(std::mt19937_64 &rng, const Field<MatchConfig> &f, MatchConfig *c, bool outside) {
  const Bounds &b = f.bounds;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (std::holds_alternative<uint64_t MatchConfig::*>(f.member)) {
    uint64_t MatchConfig::*m = std::get<uint64_t MatchConfig::*>(f.member);
    uint64_t hi = static_cast<uint64_t>(b.ihi);
    if (outside) c->*m = hi + 1 + rng() % (UINT64_MAX - hi);
    else c->*m = rng() % (hi + 1);
    return true;
  }
  if (!std::holds_alternative<double MatchConfig::*>(f.member)) return false;
  double MatchConfig::*m = std::get<double MatchConfig::*>(f.member);
  const double span = b.hi - b.lo;
  if (!outside) {
    double v = b.lo + u(rng) * span;
    c->*m = (b.lo_open && v == b.lo) || (b.hi_open && v == b.hi) ? b.lo + 0.5 * span : v;
    return true;
  }
  switch (rng() % 4) {
    case 0: c->*m = NAN; return true;
    case 1: c->*m = (rng() % 2) ? HUGE_VAL : -HUGE_VAL; return true;
    case 2: c->*m = b.lo_open ? b.lo : std::nextafter(b.lo, -HUGE_VAL) - u(rng) * span; return true;
    default: c->*m = b.hi_open ? b.hi : std::nextafter(b.hi, HUGE_VAL) + u(rng) * span; return true;
  }
}

// A MatchInfo a client uses (usable_info), the match's settings its defaults'.
MatchInfoOut usable() {
  MatchInfoOut i;
  i.players = 2;
  i.level = BALL_LEVEL_EASY;
  i.frame_time = 1.0 / 60.0;
  i.server_time = 10.0;
  ball_model_default(&i.model);
  return i;
}

}  // namespace

// The settings that travel are one list (BALL_MATCH_WIRE_SETTINGS) whose
// names are keys of the field table: each at random values of its range
// comes back the same, bit for bit, from a sample's bytes and from a record.
TEST(every_setting_that_travels_crosses_the_wire_and_the_records) {
#define BALL_ONE(f) +1
  const size_t listed = 0 BALL_MATCH_WIRE_SETTINGS(BALL_ONE);
#undef BALL_ONE
  CHECK_EQ(wire_setting_fields().size(), listed);  // every name is a key of match_fields()
  std::mt19937_64 rng(61206);
  int same = 0;
  for (int k = 0; k < 500; ++k) {
    MatchInfoOut in = usable();
    for (const auto &f : wire_setting_fields()) CHECK(draw_setting(rng, f, &in.settings, false));
    MatchInfoOut wire;
    CHECK(dds::deserialized(dds::serialized(in), &wire));
    MatchInfoOut record = nlohmann::json(in).get<MatchInfoOut>();
    bool alike = true;
#define BALL_SAME(f)                                                                                 \
  alike = alike && std::memcmp(&wire.settings.f, &in.settings.f, sizeof in.settings.f) == 0 &&        \
          std::memcmp(&record.settings.f, &in.settings.f, sizeof in.settings.f) == 0;                 \
  CHECK_MSG(alike, "info %d: %s differs after the wire or the record", k, #f);
    BALL_MATCH_WIRE_SETTINGS(BALL_SAME)
#undef BALL_SAME
    same += alike;
  }
  check::note("500 random MatchInfo: %d came back setting for setting (%zu settings travel)", same, listed);
}

// A MatchInfo is used only with every setting it carries in its key's range
// (docs/protocol.md, "Clients that trust no one"): random values inside
// are used, values beyond either finite end, NaN and infinities are not.
TEST(a_match_info_is_used_only_with_its_settings_in_range) {
  std::mt19937_64 rng(61207);
  CHECK(usable_info(usable()));
  int used = 0, refused = 0;
  for (int k = 0; k < 300; ++k) {
    for (const auto &f : wire_setting_fields()) {
      MatchInfoOut in = usable();
      CHECK(draw_setting(rng, f, &in.settings, false));
      CHECK_MSG(usable_info(in), "%s = %s inside its range, refused", f.key, value_text(f, in.settings).c_str());
      used += usable_info(in);
      MatchInfoOut out = usable();
      CHECK(draw_setting(rng, f, &out.settings, true));
      CHECK_MSG(!usable_info(out), "%s = %s outside its range, used", f.key, value_text(f, out.settings).c_str());
      refused += !usable_info(out);
    }
  }
  check::note("%d in range used, %d out of range refused", used, refused);
}

TEST(every_field_of_the_model_crosses_the_wire) {
  std::mt19937_64 rng(20261206);
  int n = 0;
  const ball_field *fields = ball_model_fields(&n);
  int same = 0;
  for (int k = 0; k < 2000; ++k) {
    MatchModelOut in;
    std::memset(&in.model, 0, sizeof in.model);
    fill(rng, &in.model, fields, n);
    in.match_id = static_cast<uint32_t>(rng());
    in.server_id = static_cast<uint32_t>(rng());
    in.model_hash = rng();
    MatchModelOut out;
    CHECK(dds::deserialized(dds::serialized(in), &out));
    std::string d = differs(&in.model, &out.model, fields, n);
    CHECK_MSG(d.empty(), "model %d: %s differs after the wire", k, d.c_str());
    CHECK(out.match_id == in.match_id && out.server_id == in.server_id && out.model_hash == in.model_hash);
    same += d.empty();
  }
  check::note("2000 random models: %d came back field for field (%d fields in the table)", same, n);
}

// Each of libball's enums of the model, at a number the IDL's long carries
// but the enum has not, in the bytes (found where two samples differing in
// that field alone differ): it comes back as a value ball_model_check names.
TEST(an_enum_out_of_range_comes_back_refused) {
  ball_model m;
  ball_model_default(&m);
  // (ball_model's enums are ints in memory: the field by its offset)
  auto field_at = [](ball_model &x, const char *name) -> int * {
    int n = 0;
    const ball_field *f = ball_model_fields(&n);
    for (int i = 0; i < n; ++i)
      if (std::string(f[i].name) == name) return reinterpret_cast<int *>(reinterpret_cast<char *>(&x) + f[i].offset);
    return nullptr;
  };
  for (const char *name : {"detect", "normal_mode", "response", "scheme", "level"}) {
    MatchModelOut a, b;
    a.model = b.model = m;
    *field_at(a.model, name) = 0;
    *field_at(b.model, name) = 1;
    std::vector<uint8_t> x = dds::serialized(a), y = dds::serialized(b);
    CHECK_EQ(x.size(), y.size());
    size_t at = 0;
    while (at < x.size() && x[at] == y[at]) ++at;
    CHECK_MSG(at + 4 <= x.size(), "%s: no byte differs", name);
    if (at + 4 > x.size()) continue;
    for (int32_t bad : {99, -1, 0x7fffffff}) {
      std::vector<uint8_t> forged = x;
      std::memcpy(&forged[at], &bad, 4);  // (the sample is little-endian CDR, as this host writes it)
      MatchModelOut out;
      CHECK(dds::deserialized(forged, &out));
      const char *field = nullptr;
      ball_status st = ball_model_check(&out.model, &field);
      CHECK_MSG(st != BALL_OK && field && std::string(field) == name, "%s = %d: %s refused as %s", name, bad,
                ball_strerror(st), field ? field : "(none)");
    }
  }
  std::vector<uint8_t> cut = dds::serialized(MatchModelOut{});
  cut.resize(cut.size() / 2);
  MatchModelOut out;
  CHECK(!dds::deserialized(cut, &out));  // a sample cut short is not one
}

TEST(a_reader_uses_a_model_only_when_it_is_the_infos) {
  ball_model m;
  ball_model_default(&m);
  MatchModelOut good;
  good.model = m;
  good.model_hash = ball_model_hash(&m);
  CHECK(usable_model(good, good.model_hash));
  CHECK(!usable_model(good, good.model_hash + 1));  // another model than the MatchInfo's
  MatchModelOut lying = good;
  lying.model.gravity = 3.7;  // under the default's hash
  CHECK(!usable_model(lying, good.model_hash));
  MatchModelOut broken = good;
  broken.model.floor_damping = 2.0;
  broken.model_hash = ball_model_hash(&broken.model);
  CHECK(!usable_model(broken, broken.model_hash));  // fails ball_model_check
  MatchModelOut nan = good;
  nan.model.mass = NAN;
  nan.model_hash = ball_model_hash(&nan.model);
  CHECK(!usable_model(nan, nan.model_hash));
}

CHECK_MAIN
