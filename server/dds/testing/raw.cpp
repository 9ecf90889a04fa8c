#include "testing/raw.h"

#include "domain_impl.h"

namespace ballsrv {
namespace dds {

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

// The Domain's entities, for the raw writers (a friend of both).
struct RawAccess {
  template <class T>
  static RawWriter make(Domain &domain, const char *topic_name, const char *profile, std::string *err);
};

template <class T>
RawWriter RawAccess::make(Domain &domain, const char *topic_name, const char *profile, std::string *err) {
  Domain::Impl *impl_ = domain.impl_.get();
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
RawWriter raw_writer(Domain &domain, const char *topic, const char *profile, std::string *err) {
  return RawAccess::make<T>(domain, topic, profile, err);
}

#define BALL_RAW(T)                                                          \
  template std::vector<uint8_t> serialized<T>(const T &);                    \
  template bool deserialized<T>(const std::vector<uint8_t> &, T *);           \
  template RawWriter raw_writer<T>(Domain &, const char *, const char *, std::string *);
BALL_RAW(RacketSampleIn)
BALL_RAW(ControlIn)
BALL_RAW(SegmentOut)
BALL_RAW(EventOut)
BALL_RAW(StateOut)
BALL_RAW(MatchInfoOut)
BALL_RAW(StatusOut)
BALL_RAW(MatchModelOut)
#undef BALL_RAW

}  // namespace dds
}  // namespace ballsrv
