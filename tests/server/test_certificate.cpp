// A certificate's subject key and the GUID prefixes that fit it
// (server/security/certificate.h), offline: a prefix made by PKI-DH's rule
// from a key fits it, and one bit changed anywhere in its 48 does not; a
// file that is missing or not a PEM certificate is named in the refusal.
#include <cstdio>
#include <string>

#include "certificate.h"
#include "check.hpp"

using namespace ballsrv;

namespace {

// PKI-DH's prefix of the holder of a certificate with `key` (bit 0 is 1,
// bits 1..47 the key's bits 0..46), the rest of the prefix `rest`
ParticipantId prefix_of(const SubjectKey &key, uint8_t rest) {
  ParticipantId p{};
  p[0] = static_cast<uint8_t>(0x80 | key[0] >> 1);
  for (int i = 1; i < 6; ++i) p[i] = static_cast<uint8_t>((key[i - 1] & 1) << 7 | key[i] >> 1);
  for (int i = 6; i < 12; ++i) p[i] = rest;
  return p;
}

}  // namespace

TEST(a_prefix_fits_its_key_and_no_other_bit) {
  const SubjectKey keys[] = {{0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC}, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFE}, {0, 0, 0, 0, 0, 0}};
  for (const SubjectKey &key : keys) {
    const ParticipantId p = prefix_of(key, 0x5A);
    CHECK(prefix_fits(p, key));
    CHECK(prefix_fits(prefix_of(key, 0x00), key));  // the last 6 bytes are the participant's own
    for (int bit = 0; bit < 48; ++bit) {
      ParticipantId q = p;
      q[bit / 8] = static_cast<uint8_t>(q[bit / 8] ^ (0x80 >> (bit % 8)));
      CHECK_MSG(!prefix_fits(q, key), "bit %d flipped still fits", bit);
    }
  }
}

TEST(a_file_that_is_no_certificate_is_named) {
  SubjectKey key{1, 2, 3, 4, 5, 6};
  std::string err;
  CHECK(!subject_key_of("/nonexistent/server1.pem", &key, &err));
  CHECK_MSG(err.find("/nonexistent/server1.pem") != std::string::npos, "%s", err.c_str());
  const std::string junk = "test_certificate_junk.pem";
  FILE *f = std::fopen(junk.c_str(), "w");
  CHECK(f != nullptr);
  if (!f) return;
  std::fputs("-----BEGIN CERTIFICATE-----\nnot base64 at all\n-----END CERTIFICATE-----\n", f);
  std::fclose(f);
  CHECK(!subject_key_of(junk, &key, &err));
  CHECK_MSG(err.find("not a PEM certificate") != std::string::npos, "%s", err.c_str());
  std::remove(junk.c_str());
  CHECK(key == (SubjectKey{1, 2, 3, 4, 5, 6}));  // refused: the key as it was
}

CHECK_MAIN
