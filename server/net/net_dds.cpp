// ball_net_open: a client of ball/net.h on a DDS participant (server/dds's
// Domain and client endpoints), its writers one pair per DDS partition.
#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <new>
#include <set>
#include <string>

#include "client_endpoints.h"
#include "domain.h"
#include "net_client.h"

using namespace ballsrv;

namespace {

static_assert(kMaxClientMatches == static_cast<size_t>(dds::kClientRoom),
              "a client's readers make room for the matches its core keeps");
constexpr int kWritersPerMatch = 1;  // a client writes one slot's samples in a match

const char *or_empty(const char *s) { return s ? s : ""; }

// The client's port: the endpoints' readers, and its writers, one pair per
// DDS partition (under DDS Security a player writes in its match's,
// match/<id>, made when first needed; on an open domain one pair). With
// `rackets`, the players' racket samples too: on an open domain the
// endpoints' one reader; under DDS Security one reader in the partition of
// each match followed, made when it is first followed. With `followed_only`,
// the endpoints read the matches followed alone, in their partitions
// (ClientEndpoints::narrow), every match while none is followed.
class NetPort : public ClientPort {
 public:
  NetPort(dds::Domain &domain, std::unique_ptr<dds::ClientEndpoints> readers, int matches, bool rackets,
          bool followed_only)
      : domain_(domain), readers_(std::move(readers)), matches_(matches), rackets_(rackets),
        followed_only_(followed_only) {}
  bool take(MatchInfoOut *i) override { return readers_->take(i); }
  bool take(SegmentOut *s) override { return readers_->take(s); }
  bool take(StateOut *s) override { return readers_->take(s); }
  bool take(EventOut *e) override { return readers_->take(e); }
  bool take(StatusOut *s) override { return readers_->take(s); }
  bool take(MatchModelOut *m) override { return readers_->take(m); }
  bool take(RacketSampleIn *s) override {
    if (!domain_.secure()) return readers_->take(s);
    for (auto &r : racket_readers_)
      if (dds::take_racket(r.second, s)) return true;
    return false;
  }
  bool follow(uint32_t match, std::string *why) override {
    if (followed_only_ && !followed_.count(match)) {
      std::set<uint32_t> more = followed_;
      more.insert(match);
      if (!readers_->narrow(more, why)) return false;
      followed_ = std::move(more);
    }
    if (!rackets_ || !domain_.secure()) return true;
    std::string partition = dds::match_partition(match);
    if (racket_readers_.count(partition)) return true;
    auto r = dds::racket_reader(domain_, 1, partition, why);
    if (!r.valid()) return false;
    racket_readers_.emplace(partition, std::move(r));
    return true;
  }
  // A port made anew takes the matches the old one followed (once, not one by one).
  bool adopt(const NetPort &old, std::string *why) {
    if (followed_only_ && !old.followed_.empty()) {
      if (!readers_->narrow(old.followed_, why)) return false;
      followed_ = old.followed_;
    }
    for (const auto &r : old.racket_readers_) {
      auto fresh = dds::racket_reader(domain_, 1, r.first, why);
      if (!fresh.valid()) return false;
      racket_readers_.emplace(r.first, std::move(fresh));
    }
    return true;
  }
  void unfollow(uint32_t match) override {
    std::string why;  // (fewer partitions than before: refused only where the domain refuses every reader)
    if (followed_only_ && followed_.erase(match) && !readers_->narrow(followed_, &why)) error_ = why;
  }
  bool write(const RacketSampleIn &s) override {
    Pair *p = pair(s.match_id);
    return p && p->samples.write(s);
  }
  bool write(const ControlIn &c) override {
    Pair *p = pair(c.match_id);
    return p && p->controls.write(c);
  }
  bool hears_server() const override { return readers_->hears_server(); }
  bool meets_server() const override { return readers_->meets_server(); }
  WireSizes sizes() const override { return sizes_; }
  uint64_t untrusted() const override { return readers_->untrusted(); }
  const std::string &error() const { return error_; }

 private:
  struct Pair {
    dds::Writer<RacketSampleIn> samples;
    dds::Writer<ControlIn> controls;
  };
  Pair *pair(uint32_t match) {
    std::string partition = domain_.secure() ? dds::match_partition(match) : "";
    auto it = pairs_.find(partition);
    if (it != pairs_.end()) return it->second.samples.valid() ? &it->second : nullptr;
    Pair &p = pairs_[partition];  // (kept even when refused: a refusal is not asked again)
    int instances = domain_.secure() ? kMaxPlayers : matches_ * kWritersPerMatch;
    p.samples = domain_.writer<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {instances, 0, partition}, &error_);
    if (p.samples.valid())
      p.controls = domain_.writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {domain_.secure() ? 1 : matches_, 0, partition},
                                             &error_);
    if (!p.controls.valid()) p.samples = dds::Writer<RacketSampleIn>();
    return p.samples.valid() ? &p : nullptr;
  }
  dds::Domain &domain_;
  std::unique_ptr<dds::ClientEndpoints> readers_;
  int matches_;
  std::map<std::string, Pair> pairs_;
  bool rackets_;
  bool followed_only_;
  std::set<uint32_t> followed_;  // (with followed_only)
  std::map<std::string, dds::Reader<RacketSampleIn>> racket_readers_;  // by partition (DDS Security)
  std::string error_;
  WireSizes sizes_ = dds::wire_sizes();
};

// A participant and its port, as ball_net_open's config asks.
struct Made {
  std::unique_ptr<dds::Domain> domain;
  std::unique_ptr<NetPort> port;
};
using Maker = std::function<ball_status(Made *, std::string *)>;

class DdsTransport : public Transport {
 public:
  DdsTransport(Made made, Maker maker) : made_(std::move(made)), maker_(std::move(maker)) {}
  ClientPort &port() override { return *made_.port; }
  ParticipantId id() const override { return made_.domain->id(); }
  std::string error() const override { return made_.port ? made_.port->error() : std::string(); }
  bool close(double limit) override { return close(&made_, limit); }
  bool renewable() const override { return made_.domain && made_.domain->connects_out(); }
  bool renew(std::string *why) override {
    Made fresh;
    if (maker_(&fresh, why) != BALL_OK) return false;
    if (!fresh.port->adopt(*made_.port, why)) {
      close(&fresh, dds::kTeardownLimit);
      return false;
    }
    std::swap(made_, fresh);
    close(&fresh, dds::kTeardownLimit);  // (the old one's: bounded, as ball_net_close's)
    return true;
  }

 private:
  static bool close(Made *m, double limit) {
    m->port.reset();  // handles only: the Domain owns the entities
    bool done = !m->domain || m->domain->close(limit);
    m->domain.reset();
    return done;
  }
  Made made_;
  Maker maker_;
};

// What makes the config's participant and port, now and whenever the
// client starts anew (the config's strings copied: the caller's may go).
Maker maker_of(const ball_net_config &config, const CoreSettings &settings) {
  dds::Security security{or_empty(config.security_dir), or_empty(config.identity), or_empty(config.tls_dir)};
  dds::Reach reach;
  reach.discovery_servers = or_empty(config.discovery_servers);
  reach.tcp_peers = or_empty(config.tcp_peers);
  std::string qos_file = or_empty(config.qos_file);
  std::string profile = config.participant ? config.participant : "loopback";
  std::string name = config.name ? config.name : "ball-net";
  const int domain_id = config.domain;
  const int matches = static_cast<int>(settings.max_matches);
  dds::ClientNeeds needs;
  needs.players = 0;  // the writers are the port's, per partition
  needs.matches = matches;
  needs.events = true;
  needs.states = config.ball_states != 0;
  needs.status = config.server_status != 0;  // (for the tap alone)
  needs.server_certs = settings.servers.bound();
  const bool rackets = settings.rackets, followed_only = config.followed_only != 0;
  return [=](Made *out, std::string *err) {
    auto domain = dds::Domain::open(domain_id, qos_file, profile, reach, name, err, security);
    if (!domain) return BALL_ENETWORK;
    dds::ClientNeeds n = needs;
    n.rackets = rackets && !domain->secure();  // (secure: a reader per match followed, NetPort)
    auto readers = dds::ClientEndpoints::open(*domain, n, err);
    if (!readers) {
      domain->close(dds::kTeardownLimit);
      return BALL_ENETWORK;
    }
    out->port = std::make_unique<NetPort>(*domain, std::move(readers), matches, rackets, followed_only);
    out->domain = std::move(domain);
    return BALL_OK;
  };
}

}  // namespace

extern "C" ball_status ball_net_open(const ball_net_config *config, ball_net_client **client, char *why,
                                     size_t why_size) {
  if (client) *client = nullptr;
  auto say = [&](ball_status st, const std::string &text) {
    if (why && why_size > 0) {
      size_t n = std::min(text.size(), why_size - 1);
      text.copy(why, n);
      why[n] = '\0';
    }
    return st;
  };
  if (!config || !client) return say(BALL_EINVAL, "config and client must not be NULL");
  try {
    if (config->domain < 0 || config->domain > kMaxDomain)
      return say(BALL_ERANGE, "domain " + std::to_string(config->domain) + " is not in [0, " + std::to_string(kMaxDomain) + "]");
    CoreSettings settings;
    std::string err;
    ball_status st = core_settings_of(*config, &settings, &err);
    if (st != BALL_OK) return say(st, err);
    Made made;
    Maker maker = maker_of(*config, settings);
    st = maker(&made, &err);
    if (st != BALL_OK) return say(st, err);
    st = open_over(std::make_unique<DdsTransport>(std::move(made), std::move(maker)), *config, client, &err);
    return say(st, st == BALL_OK ? "" : err);
  } catch (const std::bad_alloc &) {
    return say(BALL_ENOMEM, "out of memory");
  } catch (const std::exception &e) {
    return say(BALL_ENETWORK, std::string("unexpected: ") + e.what());
  } catch (...) {
    return say(BALL_ENETWORK, "unexpected failure");
  }
}
