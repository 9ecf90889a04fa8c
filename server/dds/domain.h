// The one place that knows Fast DDS: a participant on a domain with its
// publisher, subscriber, topics, writers and readers, all created from the
// XML profile file (server/qos/ball_qos.xml) and owned here. A Domain
// deletes them in reverse order (readers and writers, topics, subscriber and
// publisher, participant) when it goes; Writer and Reader are handles that
// must not outlive it. Nothing else in the project includes a DDS header.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "certificate.h"
#include "types.h"

namespace eprosima {
namespace fastdds {
namespace dds {
class DataWriter;
class DataReader;
}  // namespace dds
}  // namespace fastdds
}  // namespace eprosima

namespace ballsrv {
namespace dds {

// The QoS profiles of server/qos/ball_qos.xml, built into the code (a
// client library needs no file): the text of the file, as the build read it.
extern const char *const kBuiltinProfiles;

// Topic names (docs/protocol.md).
constexpr const char *kRacketTopic = "ball/racket_samples";
constexpr const char *kStateTopic = "ball/ball_state";
constexpr const char *kSegmentTopic = "ball/segments";
constexpr const char *kEventTopic = "ball/events";
constexpr const char *kControlTopic = "ball/match_control";
constexpr const char *kInfoTopic = "ball/match_info";
constexpr const char *kModelTopic = "ball/match_model";
constexpr const char *kStatusTopic = "ball/server_status";

// Endpoint profiles of the XML file, by purpose.
constexpr const char *kPrimaryProfile = "primary";  // a primary server's writers' ownership strength
constexpr const char *kStandbyProfile = "standby";  // a standby's, below it
constexpr const char *kRacketProfile = "racket_samples";
constexpr const char *kStateProfile = "ball_state";
constexpr const char *kSegmentProfile = "segments";
constexpr const char *kEventProfile = "events";
constexpr const char *kControlProfile = "control";
constexpr const char *kInfoProfile = "match_info";
constexpr const char *kModelProfile = "match_model";
constexpr const char *kStatusProfile = "server_status";

// Instances a client's readers make room for: the matches it may see on a
// domain (a reader without room for an instance drops its samples, counted
// as rejected, and a bot would miss its own match among many).
constexpr int kClientRoom = 4096;

// A reader's door: it sees each arriving sample's CDR body (after the
// 4-byte encapsulation) before DDS keeps it, and so before the sample's key
// becomes an instance of the reader; false turns the sample away. Called
// from DDS's receive threads. A sample that does not read as the reader's
// type (an encapsulation Fast CDR does not know, a boolean byte other than
// 0 or 1, cut short) is turned away before admit, and told to malformed().
class Door {
 public:
  virtual ~Door() = default;
  virtual bool admit(const uint8_t *body, size_t size, bool little_endian) const = 0;
  virtual void malformed() const = 0;
};

// How many instances (keys) an endpoint must hold: the profile says keep
// last N per instance; this says how many instances, and so max_samples.
// A reader with an inbox takes every sample as it arrives (in the DDS
// thread) into a queue of at most `inbox` samples, refusing (and counting
// as rejected) what does not fit; take() then reads that queue. Fast DDS
// 2.9 looks a new sample up through the reader's whole history, and
// removes a taken one likewise, so a history that holds a frame's samples
// costs O(samples^2) a frame; with an inbox it holds one or two
// (docs/server-reference.md, "Load"). Samples that find the inbox full are still
// handed out after it, marked `rejected`, up to a quarter of its size more
// (so that the loop counts each where it belongs, its stream included);
// beyond that they are a `rejected` note only.
struct Sizing {
  int instances = 1;
  int inbox = 0;          // samples; 0: samples wait in the DDS reader until taken
  int inbox_per_key = 0;  // samples of one stream (a racket sample's writer, match and slot) the inbox
                          // holds; 0: no share (one stream's burst must not take the others' room)
  std::string partition;  // the endpoint's DDS partition ("": the default one); under DDS
                          // Security a player writes only in its match's, match/<id>
  std::shared_ptr<const Door> door;  // a reader's door (none: every sample DDS takes)
  Sizing(int instances_ = 1, int inbox_ = 0, std::string partition_ = "",  // NOLINT: {n} sizes
         std::shared_ptr<const Door> door_ = nullptr)
      : instances(instances_), inbox(inbox_), partition(std::move(partition_)), door(std::move(door_)) {}
};

// The DDS partition of match `id`'s players (docs/security.md).
std::string match_partition(uint32_t id);
constexpr const char *kAnyMatchPartition = "match/*";

// DDS Security for a participant (docs/security.md): the folder of the
// certificates and signed documents (`./run certs`) and the identity in it.
// TLS on the TCP transport (docs/deploy.md) is here too: the same identity's
// certificate, checked against the folder's ca.pem both ways.
struct Security {
  std::string dir;       // "": an open domain
  std::string identity;  // NAME: NAME.pem and NAME.key in dir (and in tls_dir)
  std::string tls_dir;   // "": plain TCP; else TLS with ca.pem and the identity in this folder
};

// Where a participant reaches beyond its profile (docs/deploy.md); "" and 0
// keep the profile's.
struct Reach {
  std::string discovery_servers;  // a Discovery Server client's: HOST:PORT[;HOST:PORT...]
  std::string tcp_peers;          // a TCP profile's servers to connect to: HOST:PORT[;HOST:PORT...]
  int tcp_port = 0;               // a TCP profile's listening port, [1, 65535]
  std::string tcp_public;         // a listening TCP profile's IPv4 address as its peers reach it
};


// What DDS says about a sample besides its data.
struct SampleMeta {
  ParticipantId from{};      // the writer's participant GUID prefix
  std::array<uint8_t, 16> writer{};  // the writer's whole GUID
  double source_time = 0.0;  // writer's realtime clock at write, s since 1970
  double reception_time = 0.0;
  bool rejected = false;     // the inbox was full: handed out only to be counted (Sizing)
};

// Something the DDS threads noticed about a reader's writers; the owning
// loop drains them (Reader::drain_status).
struct StatusNote {
  enum Kind { writer_lost, deadline_missed, rejected, writer_matched, samples_lost } kind;
  ParticipantId who{};  // writer_lost/writer_matched: the participant; zeros otherwise
  int count = 1;
};

// Bytes of one sample of T as written: its CDR encoding with the 4-byte
// encapsulation header, the same for every sample (fixed-size types).
template <class T>
uint64_t serialized_size();

class Domain;

template <class T>
class Writer {
 public:
  Writer() = default;
  [[nodiscard]] bool write(const T &sample);  // false: DDS refused it (count it)
  // Asserts the writer's liveliness (a writer of manual-by-topic liveliness
  // must, within its lease, or its readers count it gone); false: refused.
  bool assert_liveliness();
  // Disposes the instance of the sample's key (its readers see it gone, a
  // late joiner is not handed it); false: refused.
  bool dispose(const T &key_sample);
  // Sets the ownership strength of a writer with exclusive ownership (a
  // mutable policy: its readers rank it anew); false: refused.
  bool set_strength(uint32_t strength);
  int matched() const;  // readers matched now
  bool valid() const { return w_ != nullptr; }

 private:
  friend class Domain;
  eprosima::fastdds::dds::DataWriter *w_ = nullptr;
};

template <class T>
class Reader {
 public:
  Reader() = default;
  // Takes one sample; false when none is left. Invalid samples (disposals,
  // unregistrations) are skipped.
  bool take(T *sample, SampleMeta *meta);
  int matched() const;  // writers matched now
  // Moves the notes the DDS threads queued since the last call into out.
  void drain_status(std::vector<StatusNote> *out);
  bool valid() const { return r_ != nullptr; }

 private:
  friend class Domain;
  eprosima::fastdds::dds::DataReader *r_ = nullptr;
  struct Notes;
  Notes *notes_ = nullptr;
};

// Fast DDS 2.9 can deadlock while it deletes entities: a timer's callback
// waits for a lock held by the thread that is unregistering a timer, which
// waits for that callback (eProsima/Fast-DDS #6193 and #6502, both open; seen
// here at the end of ball_flood, two participants in one process, under
// ASan). A Domain therefore deletes its entities through run_bounded: if that
// has not returned within kTeardownLimit seconds, the process says so on
// stderr and ends with the status given to set_exit_status_if_stuck (1
// unless a program set it; a program sets 0 once everything it had to
// write is written, so its results and its status survive the deadlock).
constexpr double kTeardownLimit = 3.0;
void set_exit_status_if_stuck(int status);
// Runs work(); if it has not returned after `limit` s, writes "<what> did
// not finish ..." to stderr, flushes stdio and calls _exit with that status.
void run_bounded(const std::function<void()> &work, double limit, const std::string &what);

class Domain {
  struct Key {};  // only open() makes a Domain

 public:
  explicit Domain(Key);
  // Loads `profile_file` (once per process; "": kBuiltinProfiles), then creates the participant
  // with `participant_profile` on `domain_id`. What `reach` gives replaces
  // the profile's: reach.discovery_servers (ROS_DISCOVERY_SERVER's syntax:
  // the n-th entry is server id n) a Discovery Server client's servers; the
  // TCP fields its TCP transport's initial peers, listening port and public
  // address. Returns nullptr with a sentence in err: a missing or invalid
  // profile file, a domain id outside [0, 232], a reach field for a profile
  // without that kind of transport or a list that cannot be read, a
  // participant that cannot be created.
  // With security.dir, the participant authenticates with the identity's
  // certificate and obeys the signed governance and permissions; with
  // security.tls_dir, its TCP connections are TLS with that certificate, and
  // a peer without one signed by ca.pem is refused (a missing file is an
  // error naming it).
  static std::unique_ptr<Domain> open(int domain_id, const std::string &profile_file,
                                      const std::string &participant_profile, const Reach &reach,
                                      const std::string &name, std::string *err, const Security &security = {});
  ~Domain();
  // Deletes the entities as the destructor does, but never ends the
  // process (for a library): false when Fast DDS did not finish within
  // `limit` s; its entities are left to it, and the Domain is closed all
  // the same (every handle of it is dead from now on).
  bool close(double limit);
  Domain(const Domain &) = delete;
  Domain &operator=(const Domain &) = delete;

  ParticipantId id() const;
  int domain_id() const { return domain_id_; }
  bool secure() const { return secure_; }
  // A TCP client: its profile's TCP transports listen on no port, every
  // connection is made out by it (a participant made anew makes new ones).
  bool connects_out() const { return connects_out_; }
  // The SubjectKey of identity NAME (NAME.pem in the security folder);
  // false with a sentence in err (an open domain, a missing or unreadable
  // certificate).
  bool subject_key(const std::string &identity, SubjectKey *out, std::string *err) const;
  // Whether the discovered remote writer `writer` writes in `partition`
  // (DDS Security has checked its permissions for every partition it names).
  bool writes_in(const std::array<uint8_t, 16> &writer, const std::string &partition) const;
  // The address remote participant `who` announced in discovery (its first
  // unicast IP locator's; zeros: none, or not discovered).
  HostAddress host_of(const ParticipantId &who) const;

  // Endpoints on `topic` with the data_writer/data_reader profile `profile`;
  // an invalid handle with err on failure. A writer with exclusive
  // ownership takes its strength from the data_writer profile `strength`
  // when one is named (kPrimaryProfile, kStandbyProfile).
  template <class T>
  Writer<T> writer(const char *topic, const char *profile, Sizing sizing, std::string *err,
                   const char *strength = nullptr);
  // The ownership strength of a data_writer profile (0: none or no such profile).
  uint32_t writer_strength(const char *profile) const;
  template <class T>
  Reader<T> reader(const char *topic, const char *profile, Sizing sizing, std::string *err);
  // Deletes an endpoint of this Domain now (its readers or writers see it
  // gone); the handle is invalid after. Harmless on an invalid handle.
  template <class T>
  void remove(Writer<T> *w) {
    remove_writer(w->w_);
    *w = Writer<T>();
  }
  template <class T>
  void remove(Reader<T> *r) {
    remove_reader(r->r_);
    *r = Reader<T>();
  }

  // The liveliness lease a data_reader profile requests (s; 0: none).
  double reader_lease(const char *profile) const;

 private:
  friend struct RawAccess;  // the tests' raw writers (testing/raw.h)
  void remove_writer(eprosima::fastdds::dds::DataWriter *w);
  void remove_reader(eprosima::fastdds::dds::DataReader *r);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int domain_id_ = 0;
  bool secure_ = false;
  bool connects_out_ = false;
  std::string security_dir_;  // absolute
};

}  // namespace dds
}  // namespace ballsrv
