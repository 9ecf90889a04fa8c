#include "domain.h"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/IContentFilter.hpp>
#include <fastdds/dds/topic/IContentFilterFactory.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <chrono>
#include <deque>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <future>
#include <iterator>
#include <thread>
#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "ball_wirePubSubTypes.h"
#include "convert.h"

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace ballsrv {
namespace dds {

// Whether a payload (its encapsulation included) reads as a sample of a type.
class Readable {
 public:
  virtual ~Readable() = default;
  virtual bool readable(const uint8_t *data, uint32_t length) const = 0;
};

// An IDL type's support whose reading never throws. Fast CDR 1.0 throws for
// an encapsulation it does not know (other than plain CDR, with or without
// its parameter-list flag, either byte order) and for a boolean byte other
// than 0 or 1; the generated support catches only a sample cut short, and
// an uncaught throw in a DDS receive thread or a take ends the process: one
// forged sample would stop every server and client on the domain. Here a
// sample that does not read is not data (DDS drops it at the take), and a
// door (DoorFilter) reads each sample through once before DDS keeps it.
template <class Idl, class Base>
class Guarded final : public Base, public Readable {
 public:
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t *payload, void *data) override {
    try {
      return Base::deserialize(payload, data);
    } catch (...) {
      return false;
    }
  }
  bool getKey(void *data, eprosima::fastrtps::rtps::InstanceHandle_t *handle, bool force_md5) override {
    try {
      return Base::getKey(data, handle, force_md5);
    } catch (...) {
      return false;
    }
  }
  bool readable(const uint8_t *data, uint32_t length) const override {
    if (length < 4) return false;
    try {
      eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char *>(const_cast<uint8_t *>(data)), length);
      eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
      cdr.read_encapsulation();
      Idl sample;  // (fixed-size types: no allocation)
      sample.deserialize(cdr);
      return true;
    } catch (...) {
      return false;
    }
  }
};

// RawWriter's type: a payload as it is, under another type's name.
class RawType final : public fdds::TopicDataType {
 public:
  explicit RawType(const std::string &name, bool keyed) {
    setName(name.c_str());
    m_typeSize = static_cast<uint32_t>(RawWriter::kRawMax);
    m_isGetKeyDefined = keyed;
  }
  bool serialize(void *data, eprosima::fastrtps::rtps::SerializedPayload_t *payload) override {
    const auto &bytes = *static_cast<const std::vector<uint8_t> *>(data);
    if (bytes.size() > payload->max_size) return false;
    std::copy(bytes.begin(), bytes.end(), payload->data);
    payload->length = static_cast<uint32_t>(bytes.size());
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t *, void *) override { return false; }
  std::function<uint32_t()> getSerializedSizeProvider(void *data) override {
    size_t n = static_cast<const std::vector<uint8_t> *>(data)->size();
    return [n] { return static_cast<uint32_t>(n); };
  }
  void *createData() override { return new std::vector<uint8_t>; }
  void deleteData(void *data) override { delete static_cast<std::vector<uint8_t> *>(data); }
  // the instance: the body's first 16 bytes (any handle does; a reader without one reads the key itself)
  bool getKey(void *data, eprosima::fastrtps::rtps::InstanceHandle_t *handle, bool) override {
    const auto &bytes = *static_cast<const std::vector<uint8_t> *>(data);
    for (size_t i = 0; i < 16; ++i) handle->value[i] = i + 4 < bytes.size() ? bytes[i + 4] : 0;
    return true;
  }
};

// Which IDL type and type support carry each server type.
template <class T>
struct Wire;
#define BALL_WIRE(T, IDL)                                                   \
  template <>                                                               \
  struct Wire<T> {                                                          \
    using Idl = balldds::IDL;                                               \
    using Support = Guarded<balldds::IDL, balldds::IDL##PubSubType>;        \
  };
BALL_WIRE(RacketSampleIn, RacketSample)
BALL_WIRE(ControlIn, MatchControl)
BALL_WIRE(SegmentOut, Segment)
BALL_WIRE(EventOut, Event)
BALL_WIRE(StateOut, BallState)
BALL_WIRE(MatchInfoOut, MatchInfo)
BALL_WIRE(StatusOut, ServerStatus)
BALL_WIRE(MatchModelOut, MatchModel)
#undef BALL_WIRE

namespace {

ParticipantId prefix_of(const eprosima::fastrtps::rtps::GUID_t &guid) {
  ParticipantId id;
  std::copy(std::begin(guid.guidPrefix.value), std::end(guid.guidPrefix.value), id.begin());
  return id;
}

double seconds(const eprosima::fastrtps::rtps::Time_t &t) { return static_cast<double>(t.to_ns()) * 1e-9; }

std::array<uint8_t, 16> guid_bytes(const eprosima::fastrtps::rtps::GUID_t &g) {
  std::array<uint8_t, 16> b;
  std::copy(std::begin(g.guidPrefix.value), std::end(g.guidPrefix.value), b.begin());
  std::copy(std::begin(g.entityId.value), std::end(g.entityId.value), b.begin() + 12);
  return b;
}

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
inline uint64_t inbox_key(const RacketSampleIn &s, const SampleMeta &m) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](uint8_t b) { h = (h ^ b) * 1099511628211ull; };
  for (uint8_t b : m.writer) mix(b);
  for (int i = 0; i < 4; ++i) mix(static_cast<uint8_t>(s.match_id >> (8 * i)));
  for (int i = 0; i < 4; ++i) mix(static_cast<uint8_t>(static_cast<uint32_t>(s.player) >> (8 * i)));
  return h;
}
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

// The partitions of the remote writers discovered (their publication data).
struct Publications : public fdds::DomainParticipantListener {
  using Guid = std::array<uint8_t, 16>;
  // a removed writer's partitions stay known for the samples of it still
  // waiting in a reader; the newest kRemovedKept only (bounded)
  static constexpr size_t kRemovedKept = 1024;
  mutable std::mutex mutex;
  std::map<Guid, std::vector<std::string>> partitions;
  std::map<Guid, std::vector<std::string>> removed;
  std::deque<Guid> removed_order;
  void on_publisher_discovery(fdds::DomainParticipant *, eprosima::fastrtps::rtps::WriterDiscoveryInfo &&info) override {
    using S = eprosima::fastrtps::rtps::WriterDiscoveryInfo;
    Guid g = guid_bytes(info.info.guid());
    std::lock_guard<std::mutex> lock(mutex);
    if (info.status != S::REMOVED_WRITER) {
      partitions[g] = info.info.m_qos.m_partition.getNames();
      return;
    }
    auto it = partitions.find(g);
    if (it == partitions.end()) return;
    if (removed.emplace(g, std::move(it->second)).second) removed_order.push_back(g);
    partitions.erase(it);
    while (removed_order.size() > kRemovedKept) {
      removed.erase(removed_order.front());
      removed_order.pop_front();
    }
  }
  const std::vector<std::string> *find(const Guid &g) const {
    auto it = partitions.find(g);
    if (it != partitions.end()) return &it->second;
    it = removed.find(g);
    return it == removed.end() ? nullptr : &it->second;
  }
};

// Doors (domain.h) as Fast DDS content filters of a class of our own: the
// filter expression is the door's index. Fast DDS evaluates a reader's
// filter before the sample enters its history (StatelessReader and
// StatefulReader, change_received), so a sample turned away never becomes
// an instance. A remote writer that does not know the class sends every
// sample (no writer-side filtering).
constexpr const char *kDoorClass = "BALL_DOOR";

struct DoorFilter final : public fdds::IContentFilter {
  std::shared_ptr<const Door> door;
  const Readable *type = nullptr;
  bool evaluate(const SerializedPayload &payload, const FilterSampleInfo &, const GUID_t &) const override {
    // what does not read as the type is turned away (and counted) here
    if (!type->readable(payload.data, payload.length)) {
      door->malformed();
      return false;
    }
    // (read as plain CDR with the parameter-list flag too, as Fast CDR reads it)
    return door->admit(payload.data + 4, payload.length - 4, (payload.data[1] & 1) != 0);
  }
};

struct DoorFactory : public fdds::IContentFilterFactory {
  std::mutex mutex;
  std::vector<std::shared_ptr<const Door>> doors;
  ReturnCode_t create_content_filter(const char *, const char *, const fdds::TopicDataType *type,
                                     const char *expression, const ParameterSeq &,
                                     fdds::IContentFilter *&filter) override {
    char *end = nullptr;
    unsigned long i = std::strtoul(expression, &end, 10);
    const Readable *readable = dynamic_cast<const Readable *>(type);
    std::lock_guard<std::mutex> lock(mutex);
    if (end == expression || *end != '\0' || i >= doors.size() || !readable)
      return ReturnCode_t::RETCODE_BAD_PARAMETER;
    DoorFilter *f = filter ? static_cast<DoorFilter *>(filter) : new DoorFilter;
    f->door = doors[i];
    f->type = readable;
    filter = f;
    return ReturnCode_t::RETCODE_OK;
  }
  ReturnCode_t delete_content_filter(const char *, fdds::IContentFilter *filter) override {
    delete static_cast<DoorFilter *>(filter);
    return ReturnCode_t::RETCODE_OK;
  }
};

struct Domain::Impl {
  fdds::DomainParticipant *participant = nullptr;
  Publications publications;
  fdds::Publisher *publisher = nullptr;
  fdds::Subscriber *subscriber = nullptr;
  std::map<std::string, fdds::Topic *> topics;
  DoorFactory doors;
  bool doors_registered = false;
  std::vector<fdds::ContentFilteredTopic *> filtered;
  std::vector<fdds::DataWriter *> writers;
  std::vector<fdds::DataReader *> readers;
  std::vector<std::shared_ptr<fdds::DataReaderListener>> listeners;

  ~Impl() {
    // reverse order of creation: endpoints, topics, publisher/subscriber, participant
    for (auto it = readers.rbegin(); it != readers.rend(); ++it) subscriber->delete_datareader(*it);
    for (auto it = writers.rbegin(); it != writers.rend(); ++it) publisher->delete_datawriter(*it);
    for (auto *f : filtered) participant->delete_contentfilteredtopic(f);
    if (doors_registered) participant->unregister_content_filter_factory(kDoorClass);
    for (auto &t : topics) participant->delete_topic(t.second);
    if (subscriber) participant->delete_subscriber(subscriber);
    if (publisher) participant->delete_publisher(publisher);
    if (participant) fdds::DomainParticipantFactory::get_instance()->delete_participant(participant);
  }

  template <class T>
  fdds::Topic *topic(const char *name, std::string *err) {
    auto it = topics.find(name);
    if (it != topics.end()) return it->second;
    fdds::TypeSupport type;
    std::shared_ptr<fdds::TopicDataType> &base = type;
    base = std::make_shared<typename Wire<T>::Support>();
    if (type.register_type(participant) != ReturnCode_t::RETCODE_OK) {
      *err = std::string("cannot register type ") + type.get_type_name();
      return nullptr;
    }
    fdds::Topic *t = participant->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (!t) {
      *err = std::string("cannot create topic ") + name;
      return nullptr;
    }
    topics[name] = t;
    return t;
  }

  // topic t behind a door (domain.h): a content filtered topic of the door's class
  fdds::ContentFilteredTopic *door(fdds::Topic *t, std::shared_ptr<const Door> d, std::string *err) {
    if (!doors_registered) {
      if (participant->register_content_filter_factory(kDoorClass, &doors) != ReturnCode_t::RETCODE_OK) {
        *err = "cannot register the door filter";
        return nullptr;
      }
      doors_registered = true;
    }
    std::string index;
    {
      std::lock_guard<std::mutex> lock(doors.mutex);
      index = std::to_string(doors.doors.size());
      doors.doors.push_back(std::move(d));
    }
    fdds::ContentFilteredTopic *f = participant->create_contentfilteredtopic(
        t->get_name() + "#door" + index, t, index, {}, kDoorClass);
    if (!f) {
      *err = "cannot create the door of " + t->get_name();
      return nullptr;
    }
    filtered.push_back(f);
    return f;
  }
};

namespace {
// why an endpoint may be refused under DDS Security
std::string denied(const std::string &partition) {
  return ": the identity's permissions do not grant it" +
         (partition.empty() ? std::string() : " in partition " + partition) + " (docs/security.md)";
}
}  // namespace

std::unique_ptr<Domain> Domain::open(int domain_id, const std::string &profile_file,
                                     const std::string &participant_profile, const std::string &discovery_servers,
                                     const std::string &name, std::string *err, const Security &security) {
  if (domain_id < 0 || domain_id > kMaxDomain) {
    *err = "domain " + std::to_string(domain_id) + " is unusable: RTPS maps domains 0 to " +
           std::to_string(kMaxDomain) + " onto UDP ports";
    return nullptr;
  }
  const bool builtin = profile_file.empty();
  const std::string profiles = builtin ? std::string("the built-in QoS profiles") : "QoS profile file " + profile_file;
  if (!builtin) {
    std::ifstream f(profile_file);
    if (!f) {
      *err = profiles + ": " + std::strerror(errno);
      return nullptr;
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
        return nullptr;
      }
      loaded.insert(profile_file);
    }
  }
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(participant_profile, qos) != ReturnCode_t::RETCODE_OK) {
    *err = profiles + ": no participant profile \"" + participant_profile + "\"";
    return nullptr;
  }
  if (!discovery_servers.empty() && !use_discovery_servers(discovery_servers, &qos, err)) {
    *err = "participant profile \"" + participant_profile + "\": " + *err;
    return nullptr;
  }
  if (!security.dir.empty() && !use_security(security, &qos, err)) return nullptr;
  qos.name(name);
  auto d = std::make_unique<Domain>(Key{});
  d->impl_ = std::make_unique<Impl>();
  d->domain_id_ = domain_id;
  d->secure_ = !security.dir.empty();
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
RawWriter Domain::raw_writer(const char *topic_name, const char *profile, std::string *err) {
  RawWriter w;
  typename Wire<T>::Support real;
  fdds::TypeSupport type(new RawType(real.getName(), real.m_isGetKeyDefined));
  if (type.register_type(impl_->participant) != ReturnCode_t::RETCODE_OK) {
    *err = std::string("cannot register a raw type as ") + real.getName();
    return w;
  }
  fdds::Topic *t = impl_->participant->create_topic(topic_name, real.getName(), fdds::TOPIC_QOS_DEFAULT);
  if (t) impl_->topics[topic_name] = t;  // (deleted with the participant's)
  fdds::DataWriterQos qos;
  if (!t || impl_->publisher->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    *err = std::string("cannot write raw payloads on ") + topic_name + " with profile " + profile;
    return w;
  }
  w.w_ = impl_->publisher->create_datawriter(t, qos);
  if (!w.w_) *err = std::string("cannot create a raw writer on ") + topic_name;
  else impl_->writers.push_back(w.w_);
  return w;
}

bool RawWriter::write(const std::vector<uint8_t> &payload) {
  if (!w_ || payload.size() > kRawMax) return false;
  return w_->write(const_cast<std::vector<uint8_t> *>(&payload));
}

int RawWriter::matched() const {
  fdds::PublicationMatchedStatus s;
  if (!w_ || w_->get_publication_matched_status(s) != ReturnCode_t::RETCODE_OK) return 0;
  return s.current_count;
}

template <class T>
std::vector<uint8_t> serialized(const T &sample) {
  typename Wire<T>::Idl wire = to_idl(sample);
  typename Wire<T>::Support support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(support.getSerializedSizeProvider(&wire)());
  if (!support.serialize(&wire, &payload)) return {};
  return std::vector<uint8_t>(payload.data, payload.data + payload.length);
}

template <class T>
bool deserialized(const std::vector<uint8_t> &bytes, T *out) {
  typename Wire<T>::Idl wire;
  typename Wire<T>::Support support;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  std::copy(bytes.begin(), bytes.end(), payload.data);
  payload.length = static_cast<uint32_t>(bytes.size());
  if (!support.deserialize(&payload, &wire)) return false;  // (the guarded support: never throws)
  from_idl(wire, out);
  return true;
}

template <class T>
uint64_t serialized_size() {
  typename Wire<T>::Idl wire;
  typename Wire<T>::Support support;
  return support.getSerializedSizeProvider(&wire)();
}

#define BALL_ENDPOINTS(T)                                                                      \
  template uint64_t serialized_size<T>();                                                      \
  template std::vector<uint8_t> serialized<T>(const T &);                                       \
  template bool deserialized<T>(const std::vector<uint8_t> &, T *);                              \
  template class Writer<T>;                                                                    \
  template class Reader<T>;                                                                    \
  template Writer<T> Domain::writer<T>(const char *, const char *, Sizing, std::string *, const char *); \
  template Reader<T> Domain::reader<T>(const char *, const char *, Sizing, std::string *);            \
  template RawWriter Domain::raw_writer<T>(const char *, const char *, std::string *);
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
