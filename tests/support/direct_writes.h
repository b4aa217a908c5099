// Whether a folder's file system takes O_DIRECT writes, for the tests of the writers that use them where allowed
// (io/src/direct_write_driver.h, io/export/src/output_file.h): ext4 does; tmpfs before Linux 6.6 refuses the open,
// some network and FUSE file systems the write.
#pragma once

#include <filesystem>

namespace throng::test {

/// True when one 4,096-byte block, aligned, is written through a descriptor opened with O_DIRECT in `folder` (the
/// probe file is removed again).
[[nodiscard]] bool takes_direct_writes(const std::filesystem::path& folder);

}  // namespace throng::test
