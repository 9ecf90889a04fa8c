#include "domain.h"

#include <algorithm>

#include "domain_impl.h"

namespace ballsrv {
namespace dds {

bool readable(const std::string &path) {
  std::ifstream f(path);
  return static_cast<bool>(f);
}

// Fast DDS wants the security files as file:// URIs of absolute paths.
std::string absolute(const std::string &dir) {
  if (dir.empty() || dir[0] == '/') return dir;
  char cwd[4096];
  return getcwd(cwd, sizeof cwd) ? std::string(cwd) + "/" + dir : dir;
}

namespace {

SampleMeta meta_of(const fdds::SampleInfo &info) {
  SampleMeta m;
  m.from = prefix_of(info.sample_identity.writer_guid());
  m.writer = guid_bytes(info.sample_identity.writer_guid());
  m.source_time = seconds(info.source_timestamp);
  m.reception_time = seconds(info.reception_timestamp);
  return m;
}

// keep-last depth per instance from the profile, instances from the caller
template <class Qos>
void size_limits(Qos *qos, Sizing sizing) {
  int depth = qos->history().kind == fdds::KEEP_LAST_HISTORY_QOS ? qos->history().depth : 64;
  if (depth < 1) depth = 1;
  int instances = sizing.instances < 1 ? 1 : sizing.instances;
  auto &rl = qos->resource_limits();
  rl.max_instances = instances;
  rl.max_samples_per_instance = depth;
  rl.max_samples = instances * depth;
  rl.allocated_samples = std::min(rl.max_samples, 256);
  // the endpoint's own partition (a Fast DDS property: DDS keeps partitions per publisher)
  if (!sizing.partition.empty()) qos->properties().properties().emplace_back("partitions", sizing.partition);
}

// The DDS Security properties of a participant (docs/security.md), or false
// with the file that is missing.
bool use_security(const Security &sec, fdds::DomainParticipantQos *qos, std::string *err) {
  if (sec.identity.empty()) {
    *err = "--secure " + sec.dir + " needs --identity NAME (NAME.pem and NAME.key in that folder)";
    return false;
  }
  std::string d = absolute(sec.dir);
  const std::string files[] = {"ca.pem", sec.identity + ".pem", sec.identity + ".key", "governance.p7s",
                               "permissions.p7s"};
  for (const auto &f : files)
    if (!readable(d + "/" + f)) {
      *err = "DDS Security: " + d + "/" + f + ": " + std::strerror(errno) + " (./run certs makes test certificates)";
      return false;
    }
  std::vector<std::pair<std::string, std::string>> props = {
      {"dds.sec.auth.plugin", "builtin.PKI-DH"},
      {"dds.sec.auth.builtin.PKI-DH.identity_ca", "file://" + d + "/ca.pem"},
      {"dds.sec.auth.builtin.PKI-DH.identity_certificate", "file://" + d + "/" + sec.identity + ".pem"},
      {"dds.sec.auth.builtin.PKI-DH.private_key", "file://" + d + "/" + sec.identity + ".key"},
      {"dds.sec.access.plugin", "builtin.Access-Permissions"},
      {"dds.sec.access.builtin.Access-Permissions.permissions_ca", "file://" + d + "/ca.pem"},
      {"dds.sec.access.builtin.Access-Permissions.governance", "file://" + d + "/governance.p7s"},
      {"dds.sec.access.builtin.Access-Permissions.permissions", "file://" + d + "/permissions.p7s"},
      {"dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC"}};
  auto &all = qos->properties().properties();
  for (const auto &p : props) {
    auto it = std::find_if(all.begin(), all.end(), [&](const eprosima::fastrtps::rtps::Property &x) {
      return x.name() == p.first;
    });
    if (it != all.end()) it->value(p.second);
    else all.emplace_back(p.first, p.second);
  }
  return true;
}

// The Discovery Servers of a client profile replaced by `list`, read by
// Fast DDS's own reader of ROS_DISCOVERY_SERVER (which Fast DDS itself
// applies only to SIMPLE participants, never to a profile that says CLIENT).
bool use_discovery_servers(const std::string &list, fdds::DomainParticipantQos *qos, std::string *err) {
  namespace rtps = eprosima::fastrtps::rtps;
  auto &discovery = qos->wire_protocol().builtin.discovery_config;
  if (discovery.discoveryProtocol != rtps::DiscoveryProtocol::CLIENT &&
      discovery.discoveryProtocol != rtps::DiscoveryProtocol::SUPER_CLIENT) {
    *err = "discovery servers \"" + list + "\" given, but the profile is not a Discovery Server client";
    return false;
  }
  rtps::RemoteServerList_t servers;
  if (!eprosima::fastdds::rtps::load_environment_server_info(list, servers) || servers.empty()) {
    *err = "discovery servers \"" + list + "\": not a list of HOST:PORT separated by ';'";
    return false;
  }
  discovery.m_DiscoveryServers = servers;
  return true;
}


}  // namespace

// The inbox's key of a sample (Sizing::inbox_per_key): a racket sample's
// stream, its writer's (match, slot), so that nobody's burst takes the
// room of another writer's stream, the holder's under the same keys
// included (FNV-1a of the writer GUID, match and slot); one key for every
// other type.
inline uint64_t writer_hash(const SampleMeta &m) {
  uint64_t h = 1469598103934665603ull;
  for (uint8_t b : m.writer) h = (h ^ b) * 1099511628211ull;
  return h;
}
inline uint64_t inbox_key(const RacketSampleIn &s, const SampleMeta &m) {
  uint64_t h = writer_hash(m);
  auto mix = [&h](uint8_t b) { h = (h ^ b) * 1099511628211ull; };
  for (int i = 0; i < 4; ++i) mix(static_cast<uint8_t>(s.match_id >> (8 * i)));
  for (int i = 0; i < 4; ++i) mix(static_cast<uint8_t>(static_cast<uint32_t>(s.player) >> (8 * i)));
  return h;
}
// A control's: its writer's, so that one writer's flood takes its own
// share of the inbox only, never another's JOIN.
inline uint64_t inbox_key(const ControlIn &, const SampleMeta &m) { return writer_hash(m); }
template <class T>
uint64_t inbox_key(const T &, const SampleMeta &) {
  return 0;
}

// What the DDS threads tell the loop about a reader's writers, and the
// reader's inbox (Sizing) when it has one.
template <class T>
struct Reader<T>::Notes : public fdds::DataReaderListener {
  std::mutex mutex;
  std::vector<StatusNote> notes;
  struct Item {
    T sample;
    SampleMeta meta;
  };
  size_t inbox_cap = 0;
  size_t per_key_cap = 0;        // of one key (inbox_key); 0: none
  std::unordered_map<uint64_t, size_t> waiting;  // per key, in the inbox now
  std::vector<Item> inbox;       // filled by the DDS thread, under mutex
  std::vector<Item> overflow;    // what found the inbox full (meta.rejected), at most inbox_cap / 4 + 1
  std::vector<Item> taken;       // the loop's: swapped with inbox when read through
  size_t next = 0;               // of taken, the next to hand out

  // Every sample that arrived, into the inbox (the DDS thread).
  void on_data_available(fdds::DataReader *r) override {
    if (inbox_cap == 0) return;
    typename Wire<T>::Idl wire;
    fdds::SampleInfo info;
    while (r->take_next_sample(&wire, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      Item it{T{}, meta_of(info)};
      from_idl(wire, &it.sample);
      std::lock_guard<std::mutex> lock(mutex);
      size_t *mine = nullptr;
      if (per_key_cap > 0) mine = &waiting[inbox_key(it.sample, it.meta)];
      if (inbox.size() < inbox_cap && (!mine || *mine < per_key_cap)) {
        if (mine) ++*mine;
        inbox.push_back(std::move(it));
      } else if (overflow.size() <= inbox_cap / 4) {
        it.meta.rejected = true;
        overflow.push_back(std::move(it));
      } else if (!notes.empty() && notes.back().kind == StatusNote::rejected) notes.back().count++;
      else notes.push_back(StatusNote{StatusNote::rejected, ParticipantId{}, 1});
    }
  }
  bool pop(T *sample, SampleMeta *meta) {
    if (next == taken.size()) {
      taken.clear();
      next = 0;
      std::lock_guard<std::mutex> lock(mutex);
      taken.swap(inbox);
      waiting.clear();
      // those that found it full arrived after all of it
      std::move(overflow.begin(), overflow.end(), std::back_inserter(taken));
      overflow.clear();
    }
    if (next == taken.size()) return false;
    *sample = std::move(taken[next].sample);
    if (meta) *meta = taken[next].meta;
    next++;
    return true;
  }

  void add(StatusNote::Kind kind, ParticipantId who, int count) {
    if (count <= 0) return;  // nothing new (DDS's total_count_change)
    std::lock_guard<std::mutex> lock(mutex);
    notes.push_back(StatusNote{kind, who, count});
  }
  void on_liveliness_changed(fdds::DataReader *, const fdds::LivelinessChangedStatus &s) override {
    if (s.not_alive_count_change > 0)
      add(StatusNote::writer_lost, prefix_of(eprosima::fastrtps::rtps::iHandle2GUID(s.last_publication_handle)), 1);
  }
  void on_subscription_matched(fdds::DataReader *, const fdds::SubscriptionMatchedStatus &s) override {
    ParticipantId who = prefix_of(eprosima::fastrtps::rtps::iHandle2GUID(s.last_publication_handle));
    if (s.current_count_change < 0) add(StatusNote::writer_lost, who, 1);
    if (s.current_count_change > 0) add(StatusNote::writer_matched, who, 1);
  }
  void on_requested_deadline_missed(fdds::DataReader *, const fdds::RequestedDeadlineMissedStatus &s) override {
    add(StatusNote::deadline_missed, ParticipantId{}, s.total_count_change);
  }
  void on_sample_rejected(fdds::DataReader *, const fdds::SampleRejectedStatus &s) override {
    add(StatusNote::rejected, ParticipantId{}, s.total_count_change);
  }
  void on_sample_lost(fdds::DataReader *, const fdds::SampleLostStatus &s) override {
    add(StatusNote::samples_lost, ParticipantId{}, s.total_count_change);
  }
};

namespace {
// why an endpoint may be refused under DDS Security
std::string denied(const std::string &partition) {
  return ": the identity's permissions do not grant it" +
         (partition.empty() ? std::string() : " in partition " + partition) + " (docs/security.md)";
}
}  // namespace

// The participant's QoS: its profile from the profile file (the built-in
// profiles when none is given; each source loaded once a process), a
// Discovery Server and DDS Security when asked for. false with err.
static bool participant_qos(const std::string &profile_file, const std::string &participant_profile,
                            const Reach &reach, const Security &security,
                            fdds::DomainParticipantQos *qos, std::string *err) {
  const bool builtin = profile_file.empty();
  const std::string profiles = builtin ? std::string("the built-in QoS profiles") : "QoS profile file " + profile_file;
  if (!builtin) {
    std::ifstream f(profile_file);
    if (!f) {
      *err = profiles + ": " + std::strerror(errno);
      return false;
    }
  }
  auto *factory = fdds::DomainParticipantFactory::get_instance();
  // Fast DDS keeps the profiles it loaded for the process: each source is loaded once
  static std::mutex load_mutex;
  static std::set<std::string> loaded;
  {
    std::lock_guard<std::mutex> lock(load_mutex);
    if (!loaded.count(profile_file)) {
      ReturnCode_t rc = builtin ? factory->load_XML_profiles_string(kBuiltinProfiles, std::strlen(kBuiltinProfiles))
                                : factory->load_XML_profiles_file(profile_file);
      if (rc != ReturnCode_t::RETCODE_OK) {
        *err = profiles + ": not a valid Fast DDS profile file";
        return false;
      }
      loaded.insert(profile_file);
    }
  }
  if (factory->get_participant_qos_from_profile(participant_profile, *qos) != ReturnCode_t::RETCODE_OK) {
    *err = profiles + ": no participant profile \"" + participant_profile + "\"";
    return false;
  }
  if ((!reach.discovery_servers.empty() && !use_discovery_servers(reach.discovery_servers, qos, err)) ||
      !use_tcp(reach, qos, err)) {
    *err = "participant profile \"" + participant_profile + "\": " + *err;
    return false;
  }
  if (!security.dir.empty() && !use_security(security, qos, err)) return false;
  if (!security.tls_dir.empty() && !use_tls(security, qos, err)) return false;
  return true;
}

std::unique_ptr<Domain> Domain::open(int domain_id, const std::string &profile_file,
                                     const std::string &participant_profile, const Reach &reach,
                                     const std::string &name, std::string *err, const Security &security) {
  if (domain_id < 0 || domain_id > kMaxDomain) {
    *err = "domain " + std::to_string(domain_id) + " is unusable: RTPS maps domains 0 to " +
           std::to_string(kMaxDomain) + " onto UDP ports";
    return nullptr;
  }
  fdds::DomainParticipantQos qos;
  if (!participant_qos(profile_file, participant_profile, reach, security, &qos, err)) return nullptr;
  qos.name(name);
  auto *factory = fdds::DomainParticipantFactory::get_instance();
  auto d = std::make_unique<Domain>(Key{});
  d->impl_ = std::make_unique<Impl>();
  d->domain_id_ = domain_id;
  d->secure_ = !security.dir.empty();
  d->connects_out_ = tcp_client_only(qos);
  d->security_dir_ = absolute(security.dir);
  d->impl_->participant = factory->create_participant(domain_id, qos, &d->impl_->publications,
                                                      fdds::StatusMask::none());
  if (!d->impl_->participant) {
    *err = "domain " + std::to_string(domain_id) +
           " is busy or unusable: no participant could be created (its UDP ports taken, the "
           "profile's transport cannot be used here" +
           std::string(security.dir.empty() ? ")" : ", or the DDS Security files do not fit: a certificate not "
                                                    "signed by ca.pem, documents not signed by it, no grant for the identity)");
    return nullptr;
  }
  d->impl_->publisher = d->impl_->participant->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  d->impl_->subscriber = d->impl_->participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (!d->impl_->publisher || !d->impl_->subscriber) {
    *err = "cannot create a publisher or subscriber";
    return nullptr;
  }
  return d;
}

namespace {
std::atomic<int> g_exit_status_if_stuck{1};
}

void set_exit_status_if_stuck(int status) { g_exit_status_if_stuck = status; }

void run_bounded(const std::function<void()> &work, double limit, const std::string &what) {
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  std::thread guard([&] {
    std::unique_lock<std::mutex> lock(m);
    if (cv.wait_for(lock, std::chrono::duration<double>(limit), [&] { return done; })) return;
    int status = g_exit_status_if_stuck;
    std::fprintf(stderr,
                 "%s did not finish within %g s (a deadlock inside Fast DDS, eProsima/Fast-DDS#6193); "
                 "exiting with status %d\n",
                 what.c_str(), limit, status);
    std::fflush(nullptr);
    _exit(status);
  });
  work();
  {
    std::lock_guard<std::mutex> lock(m);
    done = true;
  }
  cv.notify_one();
  guard.join();
}

Domain::Domain(Key) {}

bool Domain::close(double limit) {
  if (!impl_) return true;
  // the entities are deleted on a thread of their own that this one waits for at most `limit`
  std::shared_ptr<Impl> impl(impl_.release());
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  std::thread worker([impl, done]() mutable {
    impl.reset();
    done->set_value();
  });
  impl.reset();
  if (finished.wait_for(std::chrono::duration<double>(limit)) == std::future_status::ready) {
    worker.join();
    return true;
  }
  worker.detach();  // (stuck inside Fast DDS: its entities are left to it)
  return false;
}

void Domain::remove_writer(fdds::DataWriter *w) {
  if (!w || !impl_) return;
  auto &ws = impl_->writers;
  ws.erase(std::remove(ws.begin(), ws.end(), w), ws.end());
  impl_->publisher->delete_datawriter(w);
}

void Domain::remove_reader(fdds::DataReader *r) {
  if (!r || !impl_) return;
  auto &rs = impl_->readers;
  rs.erase(std::remove(rs.begin(), rs.end(), r), rs.end());
  const fdds::DataReaderListener *l = r->get_listener();
  impl_->subscriber->delete_datareader(r);
  auto &ls = impl_->listeners;  // (after the reader: DDS calls it until then)
  ls.erase(std::remove_if(ls.begin(), ls.end(), [l](const auto &p) { return p.get() == l; }), ls.end());
}

Domain::~Domain() {
  if (!impl_ || !impl_->participant) return;
  std::string name = impl_->participant->get_qos().name().c_str();
  run_bounded([this] { impl_.reset(); }, kTeardownLimit,
              "deleting the DDS entities of participant \"" + name + "\" (domain " + std::to_string(domain_id_) +
                  ")");
}

ParticipantId Domain::id() const { return prefix_of(impl_->participant->guid()); }

bool Domain::subject_key(const std::string &identity, SubjectKey *out, std::string *err) const {
  if (!secure_) {
    *err = "the certificate of " + identity + " binds a server only under DDS Security (--secure DIR)";
    return false;
  }
  return subject_key_of(security_dir_ + "/" + identity + ".pem", out, err);
}

bool Domain::writes_in(const std::array<uint8_t, 16> &writer, const std::string &partition) const {
  std::lock_guard<std::mutex> lock(impl_->publications.mutex);
  const std::vector<std::string> *names = impl_->publications.find(writer);
  return names && std::find(names->begin(), names->end(), partition) != names->end();
}

HostAddress Domain::host_of(const ParticipantId &who) const { return impl_->publications.host_of(who); }

std::string match_partition(uint32_t id) { return "match/" + std::to_string(id); }

double Domain::reader_lease(const char *profile) const {
  fdds::DataReaderQos qos;
  if (impl_->subscriber->get_datareader_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) return 0.0;
  const auto &p = qos.liveliness().lease_duration;
  if (p == eprosima::fastrtps::c_TimeInfinite) return 0.0;
  return p.seconds + p.nanosec * 1e-9;
}

uint32_t Domain::writer_strength(const char *profile) const {
  fdds::DataWriterQos qos;
  if (impl_->publisher->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) return 0;
  return qos.ownership_strength().value;
}

template <class T>
Writer<T> Domain::writer(const char *topic_name, const char *profile, Sizing sizing, std::string *err,
                         const char *strength) {
  Writer<T> w;
  fdds::Topic *t = impl_->topic<T>(topic_name, err);
  if (!t) return w;
  fdds::DataWriterQos qos;
  if (impl_->publisher->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    *err = std::string("no data_writer profile \"") + profile + "\" in the QoS profile file";
    return w;
  }
  if (strength && qos.ownership().kind == fdds::EXCLUSIVE_OWNERSHIP_QOS) {
    fdds::DataWriterQos role;
    if (impl_->publisher->get_datawriter_qos_from_profile(strength, role) != ReturnCode_t::RETCODE_OK) {
      *err = std::string("no data_writer profile \"") + strength + "\" in the QoS profile file";
      return w;
    }
    qos.ownership_strength() = role.ownership_strength();
  }
  size_limits(&qos, sizing);
  w.w_ = impl_->publisher->create_datawriter(t, qos);
  if (!w.w_) {
    *err = std::string("cannot create a writer on ") + topic_name + " with profile " + profile;
    if (secure_) *err += denied(sizing.partition);
    return w;
  }
  impl_->writers.push_back(w.w_);
  return w;
}

template <class T>
Reader<T> Domain::reader(const char *topic_name, const char *profile, Sizing sizing, std::string *err) {
  Reader<T> r;
  fdds::Topic *t = impl_->topic<T>(topic_name, err);
  if (!t) return r;
  fdds::DataReaderQos qos;
  if (impl_->subscriber->get_datareader_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    *err = std::string("no data_reader profile \"") + profile + "\" in the QoS profile file";
    return r;
  }
  size_limits(&qos, sizing);
  fdds::TopicDescription *description = t;
  if (sizing.door) {
    description = impl_->door(t, sizing.door, err);
    if (!description) return r;
  }
  auto notes = std::make_shared<typename Reader<T>::Notes>();
  notes->inbox_cap = static_cast<size_t>(std::max(0, sizing.inbox));
  notes->per_key_cap = static_cast<size_t>(std::max(0, sizing.inbox_per_key));
  fdds::StatusMask mask = fdds::StatusMask::liveliness_changed() << fdds::StatusMask::subscription_matched()
                          << fdds::StatusMask::requested_deadline_missed() << fdds::StatusMask::sample_rejected()
                          << fdds::StatusMask::sample_lost();
  if (sizing.inbox > 0) mask << fdds::StatusMask::data_available();
  r.r_ = impl_->subscriber->create_datareader(description, qos, notes.get(), mask);
  if (!r.r_) {
    *err = std::string("cannot create a reader on ") + topic_name + " with profile " + profile;
    if (secure_) *err += denied(sizing.partition);
    return r;
  }
  r.notes_ = notes.get();
  impl_->listeners.push_back(notes);
  impl_->readers.push_back(r.r_);
  return r;
}

template <class T>
bool Writer<T>::write(const T &sample) {
  typename Wire<T>::Idl wire = to_idl(sample);
  return w_ && w_->write(&wire);
}

template <class T>
bool Writer<T>::dispose(const T &key_sample) {
  typename Wire<T>::Idl wire = to_idl(key_sample);
  return w_ && w_->dispose(&wire, eprosima::fastrtps::rtps::c_InstanceHandle_Unknown) == ReturnCode_t::RETCODE_OK;
}

template <class T>
bool Writer<T>::assert_liveliness() {
  return w_ && w_->assert_liveliness() == ReturnCode_t::RETCODE_OK;
}

template <class T>
bool Writer<T>::set_strength(uint32_t strength) {
  if (!w_) return false;
  fdds::DataWriterQos qos = w_->get_qos();
  if (qos.ownership().kind != fdds::EXCLUSIVE_OWNERSHIP_QOS) return true;
  if (qos.ownership_strength().value == strength) return true;
  qos.ownership_strength().value = strength;
  return w_->set_qos(qos) == ReturnCode_t::RETCODE_OK;
}

template <class T>
int Writer<T>::matched() const {
  fdds::PublicationMatchedStatus s;
  if (!w_ || w_->get_publication_matched_status(s) != ReturnCode_t::RETCODE_OK) return 0;
  return s.current_count;
}

template <class T>
bool Reader<T>::take(T *sample, SampleMeta *meta) {
  if (!r_) return false;
  if (notes_ && notes_->inbox_cap > 0) return notes_->pop(sample, meta);
  typename Wire<T>::Idl wire;
  fdds::SampleInfo info;
  while (r_->take_next_sample(&wire, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    *sample = T{};
    from_idl(wire, sample);
    if (meta) *meta = meta_of(info);
    return true;
  }
  return false;
}

template <class T>
int Reader<T>::matched() const {
  fdds::SubscriptionMatchedStatus s;
  if (!r_ || r_->get_subscription_matched_status(s) != ReturnCode_t::RETCODE_OK) return 0;
  return s.current_count;
}

template <class T>
void Reader<T>::drain_status(std::vector<StatusNote> *out) {
  if (!notes_) return;
  std::lock_guard<std::mutex> lock(notes_->mutex);
  out->insert(out->end(), notes_->notes.begin(), notes_->notes.end());
  notes_->notes.clear();
}

template <class T>
uint64_t serialized_size() {
  typename Wire<T>::Idl wire;
  typename Wire<T>::Support support;
  return support.getSerializedSizeProvider(&wire)();
}

#define BALL_ENDPOINTS(T)                                                                      \
  template uint64_t serialized_size<T>();                                                      \
  template class Writer<T>;                                                                    \
  template class Reader<T>;                                                                    \
  template Writer<T> Domain::writer<T>(const char *, const char *, Sizing, std::string *, const char *); \
  template Reader<T> Domain::reader<T>(const char *, const char *, Sizing, std::string *);
BALL_ENDPOINTS(RacketSampleIn)
BALL_ENDPOINTS(ControlIn)
BALL_ENDPOINTS(SegmentOut)
BALL_ENDPOINTS(EventOut)
BALL_ENDPOINTS(StateOut)
BALL_ENDPOINTS(MatchInfoOut)
BALL_ENDPOINTS(StatusOut)
BALL_ENDPOINTS(MatchModelOut)
#undef BALL_ENDPOINTS

}  // namespace dds
}  // namespace ballsrv
