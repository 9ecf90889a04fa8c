// A participant's certificate and its GUID prefix under DDS Security, free
// of DDS (OpenSSL only): PKI-DH makes the first 47 bits of a participant's
// GUID prefix those of the SHA-256 of its certificate's subject name, and
// authentication refuses a participant whose prefix does not fit the
// certificate it proves to hold; so the prefix of a sample's writer on a
// secure domain says whose certificate wrote it (docs/protocol.md, "A
// secure domain"). A SubjectKey is those 47 bits (the last one 0).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "types.h"

namespace ballsrv {

using SubjectKey = std::array<uint8_t, 6>;

// The SubjectKey of the PEM certificate in `file`; false with a sentence
// naming the file (missing, not a PEM certificate).
bool subject_key_of(const std::string &file, SubjectKey *out, std::string *err);

// Whether a participant GUID prefix is the one PKI-DH gives the holder of
// a certificate with this key (DDS Security 1.1, 9.3.3: bit 0 of the
// prefix is 1, bits 1..47 are bits 0..46 of the subject name's SHA-256).
bool prefix_fits(const ParticipantId &prefix, const SubjectKey &key);

}  // namespace ballsrv
