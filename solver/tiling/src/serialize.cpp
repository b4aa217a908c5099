#include "serialize.h"

#include "bytes.h"

namespace throng::tiling {

std::vector<std::byte> to_bytes(const ChainResult& result) {
  std::vector<std::byte> bytes;
  ByteWriter w(bytes);
  w.put(result.report);
  const Tiling& t = result.tiling;
  w.put<std::uint64_t>(t.instances.size());
  for (const Instance& inst : t.instances) {
    w.put<std::uint64_t>(inst.type);
    w.put(inst.transform.translation.x());
    w.put(inst.transform.translation.y());
    w.put(inst.transform.angle);
    w.put(inst.transform.time_shift);
    w.put<std::uint8_t>(inst.keyframed ? 1 : 0);
    w.put<std::uint64_t>(inst.paths.size());
    for (const Path& p : inst.paths) put_path(w, p);
  }
  w.put_vector(t.connections);
  return bytes;
}

ChainResult from_bytes(const std::vector<std::byte>& bytes) {
  std::size_t at = 0;
  ByteReader r(bytes, at, "a chain's result from another rank");
  ChainResult out;
  out.report = r.get<ChainReport>();
  Tiling& t = out.tiling;
  t.instances.resize(r.count(1));
  for (Instance& inst : t.instances) {
    inst.type = r.get<std::uint64_t>();
    inst.transform.translation.x() = r.get<double>();
    inst.transform.translation.y() = r.get<double>();
    inst.transform.angle = r.get<double>();
    inst.transform.time_shift = r.get<double>();
    inst.keyframed = r.get<std::uint8_t>() != 0;
    inst.paths.resize(r.count(1));
    for (Path& p : inst.paths) p = get_path(r);
  }
  t.connections = r.get_vector<Connection>();
  return out;
}

}  // namespace throng::tiling
