#pragma once
// Checks an encoded LCM message before it is decoded. LCM's generated decoders allocate what a message
// declares (an image's `size`, a detection count) before they look at the bytes that follow, so one
// 83-byte message declaring 2^31-1 bytes makes a process allocate 2 GB, and a negative count throws from
// deep inside std::vector. Here every declared length and count is checked against the bytes actually
// received, and the type's fingerprint against the expected type, without allocating anything; only a
// message that passes is handed to the generated decoder, so decoding allocates at most about the
// message's own size.
#include <cstddef>
#include <exception>
#include <string>

namespace bmp::wire {

// "" when data holds exactly one encoded Msg whose lengths and counts all fit the bytes received; else
// why not, naming the field ("image_t.size = -1", "3 trailing bytes", "fingerprint of another type").
// Specialised for every type in lcmtypes/ (a new type without one does not link).
template <typename Msg>
std::string check(const void* data, std::size_t size);

// check(), then the generated decoder. Returns false and sets why when the message is not a valid Msg.
template <typename Msg>
bool decode(Msg& out, const void* data, std::size_t size, std::string& why) {
  why = check<Msg>(data, size);
  if (!why.empty()) return false;
  try {
    const int status = out.decode(data, 0, static_cast<int>(size));
    if (status < 0 || static_cast<std::size_t>(status) != size) {
      why = "the decoder refused it";
      return false;
    }
  } catch (const std::exception& e) {  // belt and braces: check() should have caught it
    why = std::string("the decoder threw: ") + e.what();
    return false;
  }
  return true;
}

}  // namespace bmp::wire
