// The DDS adapter's own internals, shared by its files (domain.cpp, the
// tests' raw writers in testing/): the type supports that never throw
// (Guarded), which IDL type carries each server type (Wire), the
// partitions of the writers discovered, the doors as content filters, and
// the entities a Domain owns (Domain::Impl). Included by server/dds only.
#pragma once

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
#include <fastdds/rtps/transport/TCPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <arpa/inet.h>
#include <sstream>
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
#include "domain.h"


namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

namespace ballsrv {
namespace dds {

inline ParticipantId prefix_of(const eprosima::fastrtps::rtps::GUID_t &guid) {
  ParticipantId id{};
  std::copy(std::begin(guid.guidPrefix.value), std::end(guid.guidPrefix.value), id.begin());
  return id;
}

inline double seconds(const eprosima::fastrtps::rtps::Time_t &t) { return static_cast<double>(t.to_ns()) * 1e-9; }

inline std::array<uint8_t, 16> guid_bytes(const eprosima::fastrtps::rtps::GUID_t &g) {
  std::array<uint8_t, 16> b{};
  std::copy(std::begin(g.guidPrefix.value), std::end(g.guidPrefix.value), b.begin());
  std::copy(std::begin(g.entityId.value), std::end(g.entityId.value), b.begin() + 12);
  return b;
}

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

// The partitions of the remote writers discovered (their publication
// data), and the address each remote participant announced.
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
  // participant -> its first unicast IP locator's address (metatraffic,
  // then default); at most kHostsKept participants (the rest: unknown)
  static constexpr size_t kHostsKept = 4096;
  std::map<ParticipantId, HostAddress> hosts;
  void on_participant_discovery(fdds::DomainParticipant *,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo &&info) override {
    using S = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
    ParticipantId who = prefix_of(info.info.m_guid);
    std::lock_guard<std::mutex> lock(mutex);
    if (info.status == S::REMOVED_PARTICIPANT || info.status == S::DROPPED_PARTICIPANT) {
      hosts.erase(who);
      return;
    }
    if (hosts.size() >= kHostsKept && !hosts.count(who)) return;
    auto announced = [](const eprosima::fastrtps::rtps::RemoteLocatorList &list, HostAddress *out) {
      for (const auto &l : list.unicast) {
        bool ip = l.kind == LOCATOR_KIND_UDPv4 || l.kind == LOCATOR_KIND_TCPv4 || l.kind == LOCATOR_KIND_UDPv6 ||
                  l.kind == LOCATOR_KIND_TCPv6;
        if (ip && std::any_of(l.address, l.address + 16, [](uint8_t b) { return b != 0; })) {
          std::copy(l.address, l.address + 16, out->begin());
          return true;
        }
      }
      return false;
    };
    HostAddress a{};
    if (announced(info.info.metatraffic_locators, &a) || announced(info.info.default_locators, &a)) hosts[who] = a;
  }
  HostAddress host_of(const ParticipantId &who) const {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = hosts.find(who);
    return it == hosts.end() ? HostAddress{} : it->second;
  }
  const std::vector<std::string> *find(const Guid &g) const {
    auto it = partitions.find(g);
    if (it != partitions.end()) return &it->second;
    it = removed.find(g);
    return it == removed.end() ? nullptr : &it->second;
  }
};

// A readable file; a folder made absolute (Fast DDS wants file:// URIs of
// absolute paths). (domain.cpp)
bool readable(const std::string &path);
std::string absolute(const std::string &dir);
// The TCP fields of `reach` and TLS over a profile's participant QoS, or
// false with err (transport.cpp).
bool use_tcp(const Reach &reach, fdds::DomainParticipantQos *qos, std::string *err);
// Whether the participant's transports are TCPv4 ones listening on no port.
bool tcp_client_only(const fdds::DomainParticipantQos &qos);
bool use_tls(const Security &sec, fdds::DomainParticipantQos *qos, std::string *err);

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

}  // namespace dds
}  // namespace ballsrv
