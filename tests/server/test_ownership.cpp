// Exclusive ownership as the QoS file sets it up (docs/protocol.md,
// "Several servers on one domain"): two servers' writers of one match's
// MatchInfo (and MatchModel) writing at once, a reader with the QoS file's
// reader profile takes the stronger writer's samples only; a writer whose
// strength is raised while it runs (Writer::set_strength) is taken from
// then on. Fails with the readers' history of 1 sample per instance: Fast
// DDS 2.9's reader lets the weaker writer's sample push the owner's out of
// the history before it is taken, then drops it, so a reader takes nothing
// while both write. Three participants of one process on loopback.
#include <unistd.h>

#include <string>

#include "check.hpp"
#include "common.h"
#include "domain.h"

using namespace ballsrv;
using namespace ballsrv::dds;

namespace {

// 20 rounds of 0.1 s, each a sample of match 1 from both writers (the
// stronger-to-be first, then the other): the samples of each the reader took.
template <class T>
std::pair<int, int> rounds(Writer<T> &a, Writer<T> &b, Reader<T> &r) {
  int from_a = 0, from_b = 0;
  for (int k = 0; k < 20; ++k) {
    T s{};
    s.match_id = 1;
    s.server_id = 1;
    CHECK(a.write(s));
    s.server_id = 2;
    CHECK(b.write(s));
    a.assert_liveliness();
    b.assert_liveliness();
    usleep(100000);
    T got{};
    SampleMeta meta;
    while (r.take(&got, &meta)) (got.server_id == 1 ? from_a : from_b)++;
  }
  return {from_a, from_b};
}

template <class T>
void two_writers(const char *topic, const char *profile) {
  std::string err;
  const std::string qos = app::find_profile("");
  auto pa = Domain::open(BALL_TEST_DOMAIN, qos, "loopback", {}, "ownership a", &err);
  auto pb = Domain::open(BALL_TEST_DOMAIN, qos, "loopback", {}, "ownership b", &err);
  auto pc = Domain::open(BALL_TEST_DOMAIN, qos, "loopback", {}, "ownership reader", &err);
  CHECK_MSG(pa && pb && pc, "%s", err.c_str());
  if (!pa || !pb || !pc) return;
  Writer<T> a = pa->writer<T>(topic, profile, {4}, &err, kPrimaryProfile);
  Writer<T> b = pb->writer<T>(topic, profile, {4}, &err, kStandbyProfile);
  Reader<T> r = pc->reader<T>(topic, profile, {4}, &err);
  CHECK_MSG(a.valid() && b.valid() && r.valid(), "%s", err.c_str());
  if (!a.valid() || !b.valid() || !r.valid()) return;
  for (int k = 0; k < 50 && (r.matched() < 2 || a.matched() < 1 || b.matched() < 1); ++k) usleep(100000);
  const uint32_t primary = pa->writer_strength(kPrimaryProfile);
  // the primary (20) over the standby (10), both writing
  std::pair<int, int> at_start = rounds(a, b, r);
  // the standby raised above the primary while both run
  CHECK(b.set_strength(primary + 100));
  std::pair<int, int> raised = rounds(b, a, r);
  // and the primary above it again
  CHECK(a.set_strength(primary + 200));
  std::pair<int, int> again = rounds(a, b, r);
  check::note("%s, samples of the primary / the standby taken: both writing %d / %d; the standby raised %d / %d; the "
              "primary raised %d / %d",
              topic, at_start.first, at_start.second, raised.second, raised.first, again.first, again.second);
  CHECK(at_start.first >= 15 && at_start.second == 0);
  CHECK(raised.first >= 15 && raised.second <= 2);  // (a sample of the old owner's may still be on its way)
  CHECK(again.first >= 15 && again.second <= 2);
}

}  // namespace

TEST(match_info_of_two_writers_is_the_strongers) { two_writers<MatchInfoOut>(kInfoTopic, kInfoProfile); }
TEST(match_model_of_two_writers_is_the_strongers) { two_writers<MatchModelOut>(kModelTopic, kModelProfile); }

CHECK_MAIN
