#include "certificate.h"

#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace ballsrv {

bool subject_key_of(const std::string &file, SubjectKey *out, std::string *err) {
  FILE *f = std::fopen(file.c_str(), "r");
  if (!f) {
    *err = "DDS Security: " + file + ": " + std::strerror(errno);
    return false;
  }
  X509 *cert = PEM_read_X509(f, nullptr, nullptr, nullptr);
  std::fclose(f);
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  bool ok = cert && X509_NAME_digest(X509_get_subject_name(cert), EVP_sha256(), md, &length) && length >= 6;
  X509_free(cert);
  if (!ok) {
    *err = "DDS Security: " + file + ": not a PEM certificate";
    return false;
  }
  md[5] &= 0xFE;
  std::copy(md, md + 6, out->begin());
  return true;
}

bool prefix_fits(const ParticipantId &p, const SubjectKey &key) {
  for (int i = 0; i < 6; ++i) {
    uint8_t b = static_cast<uint8_t>((p[i] << 1) | (i < 5 ? p[i + 1] >> 7 : 0));
    if (b != key[i]) return false;
  }
  return (p[0] & 0x80) != 0;
}

}  // namespace ballsrv
