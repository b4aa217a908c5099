#include "serialize.h"

#include <cassert>
#include <cstring>
#include <type_traits>

namespace throng::tiling {
namespace {

class Writer {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    put<std::uint64_t>(v.size());
    for (const T& x : v) put(x);
  }
  std::vector<std::byte> bytes;
};

class Reader {
 public:
  explicit Reader(const std::vector<std::byte>& b) : bytes_(b) {}
  template <class T>
  T get() {
    T v;
    assert(at_ + sizeof(T) <= bytes_.size());
    std::memcpy(static_cast<void*>(&v), bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    std::vector<T> v(get<std::uint64_t>());
    for (T& x : v) x = get<T>();
    return v;
  }

 private:
  const std::vector<std::byte>& bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<std::byte> to_bytes(const ChainResult& result) {
  Writer w;
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
    for (const Path& p : inst.paths) {
      w.put<std::uint64_t>(p.positions.size());
      for (const Eigen::Vector2d& q : p.positions) {
        w.put(q.x());
        w.put(q.y());
      }
      w.put_vector(p.headings);
      w.put_vector(p.times);
    }
  }
  w.put_vector(t.connections);
  return std::move(w.bytes);
}

ChainResult from_bytes(const std::vector<std::byte>& bytes) {
  Reader r(bytes);
  ChainResult out;
  out.report = r.get<ChainReport>();
  Tiling& t = out.tiling;
  t.instances.resize(r.get<std::uint64_t>());
  for (Instance& inst : t.instances) {
    inst.type = r.get<std::uint64_t>();
    inst.transform.translation.x() = r.get<double>();
    inst.transform.translation.y() = r.get<double>();
    inst.transform.angle = r.get<double>();
    inst.transform.time_shift = r.get<double>();
    inst.keyframed = r.get<std::uint8_t>() != 0;
    inst.paths.resize(r.get<std::uint64_t>());
    for (Path& p : inst.paths) {
      p.positions.resize(r.get<std::uint64_t>());
      for (Eigen::Vector2d& q : p.positions) {
        q.x() = r.get<double>();
        q.y() = r.get<double>();
      }
      p.headings = r.get_vector<double>();
      p.times = r.get_vector<double>();
    }
  }
  t.connections = r.get_vector<Connection>();
  return out;
}

}  // namespace throng::tiling
