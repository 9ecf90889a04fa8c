// What only the tests' hostile participants write (tests/server: flood,
// unreadable, intrude): a sample's bytes as they go on the wire, changed at
// will, and a writer of payloads as they are under an IDL type's name. A
// library of its own (ball_dds_testing) that no program links.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "domain.h"

namespace ballsrv {
namespace dds {

// One sample of T as a writer puts it on the wire: its CDR encoding with
// the 4-byte encapsulation header.
template <class T>
std::vector<uint8_t> serialized(const T &sample);

// A sample's bytes as a reader takes them (serialized's inverse, through
// the same guarded type support); false for bytes that do not read as T.
template <class T>
bool deserialized(const std::vector<uint8_t> &bytes, T *out);

// Writes payloads as they are, their 4-byte encapsulation included, under
// the type name of an IDL type: what no IDL type writes (an encapsulation
// Fast CDR does not know, a boolean byte of 2, a sample cut short).
class RawWriter {
 public:
  RawWriter() = default;
  [[nodiscard]] bool write(const std::vector<uint8_t> &payload);  // at most kRawMax bytes
  int matched() const;  // readers matched now
  bool valid() const { return w_ != nullptr; }
  static constexpr size_t kRawMax = 4096;

 private:
  friend struct RawAccess;
  eprosima::fastdds::dds::DataWriter *w_ = nullptr;
};

// A RawWriter on `topic` of `domain` under the type name of T's IDL type,
// with the data_writer profile `profile`; invalid with err on failure. The
// participant must not have T's own type (a Domain of its own): DDS keeps
// one type per name.
template <class T>
RawWriter raw_writer(Domain &domain, const char *topic, const char *profile, std::string *err);

}  // namespace dds
}  // namespace ballsrv
