// A temporary cap on the process's address space around one libhdf5 call that converts variable-length data.
//
// libhdf5 1.10 (Debian 12) converts a variable-length string by asking for the length its 16-byte descriptor
// states and zeroing that buffer before it reads the heap object (H5T__conv_vlen): a crafted descriptor of 4 GB
// in a 60 KB file made `throng check-tiling` hold 4 GB for 20 s before it failed on the heap. Nothing in the API
// shows a descriptor before the conversion, so the conversion runs under RLIMIT_AS = the address space in use +
// `allowance`: the oversized request fails inside libhdf5, which reports a read error (InputError for us) without
// touching the memory. Legitimate strings need at most the global heap's checked size (io/src/global_heap_check.h).
//
// The cap is process-wide while it lasts: it is meant for the few microseconds of a string read, made by the
// thread that reads the file while no method runs. Where the limit cannot be read or set (or is already lower),
// nothing changes.
#pragma once

#include <cstdint>

namespace throng::h5 {

class AddressSpaceCap {
 public:
  explicit AddressSpaceCap(std::uint64_t allowance_bytes);
  ~AddressSpaceCap();
  AddressSpaceCap(const AddressSpaceCap&) = delete;
  AddressSpaceCap& operator=(const AddressSpaceCap&) = delete;

 private:
  bool capped_ = false;
  std::uint64_t previous_soft_ = 0;
};

}  // namespace throng::h5
