// Fuzz target: import_real_dataset on arbitrary bytes (corpus: tests/fuzz/corpus/real_dataset).
//
// One input holds a dataset folder's three files, separated by lines "--8<-- map.xml" and "--8<-- groups.txt":
// obsmat.txt first, then map.xml and groups.txt when their separator is present. They are written into a
// folder named "hotel" (a known dataset, so the frame rate is known) that the process creates once.
#include "fuzz_input.h"

#include <throng/io/real_dataset.h>

#include <fstream>
#include <string_view>

namespace {

const std::filesystem::path& dataset_folder() {
  static const std::filesystem::path folder = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "throng-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) std::abort();
    const std::filesystem::path hotel = std::filesystem::path(pattern) / "hotel";
    std::filesystem::create_directory(hotel);
    return hotel;
  }();
  return folder;
}

void write_or_remove(const std::filesystem::path& path, std::string_view text, bool present) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  if (present) std::ofstream(path, std::ios::binary).write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view map_mark = "\n--8<-- map.xml\n", groups_mark = "\n--8<-- groups.txt\n";
  const std::size_t map_at = all.find(map_mark), groups_at = all.find(groups_mark);
  const std::size_t obsmat_end = std::min(map_at, groups_at);
  const std::string_view obsmat = all.substr(0, obsmat_end);
  std::string_view map, groups;
  if (map_at != std::string_view::npos) {
    const std::size_t start = map_at + map_mark.size();
    map = all.substr(start, groups_at > map_at && groups_at != std::string_view::npos ? groups_at - start : std::string_view::npos);
  }
  if (groups_at != std::string_view::npos) {
    const std::size_t start = groups_at + groups_mark.size();
    groups = all.substr(start, map_at > groups_at && map_at != std::string_view::npos ? map_at - start : std::string_view::npos);
  }
  const std::filesystem::path& folder = dataset_folder();
  write_or_remove(folder / "obsmat.txt", obsmat, true);
  write_or_remove(folder / "map.xml", map, map_at != std::string_view::npos);
  write_or_remove(folder / "groups.txt", groups, groups_at != std::string_view::npos);
  throng::fuzz::expect_only_throng_errors(
      [&] { (void)throng::import_real_dataset(folder, throng::RealDatasetOptions{}, throng::fuzz::fuzz_limits()); });
  return 0;
}
