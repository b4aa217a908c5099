// GLB layout: header, JSON chunk, BIN chunk. The BIN chunk holds, 4-byte aligned: the frame times (float[T],
// shared by every translation and rotation sampler), the proxy mesh (positions, uint16 indices), then per agent
// its translations (float[T][3]) and rotations (float[T][4]), then the scale keys of agents that are absent
// somewhere (key times, float[K], and scales, float[K][3]). Every size is known before the first byte (the keys
// come from a pass over presence), so the JSON goes first and the data streams after it, agent group by group.
#include "agent_poses.h"
#include "agent_ranges.h"
#include "block_stream.h"
#include "output_file.h"
#include "proxy_mesh.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/io/export/gltf.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cstring>
#include <string>
#include <vector>

namespace throng {
namespace {

using nlohmann::json;

constexpr std::uint32_t glb_magic = 0x46546C67;  // "glTF"
constexpr std::uint32_t chunk_json = 0x4E4F534A;
constexpr std::uint32_t chunk_bin = 0x004E4942;
constexpr int float_type = 5126, ushort_type = 5123;
constexpr std::size_t group_bytes = 8 << 20;  // animation data assembled per group of agents

// World (z up) → glTF (y up): (x, y, z) → (x, z, −y), a rotation of −90° about x.
Eigen::Vector3d to_gltf(const Eigen::Vector3d& p) { return {p.x(), p.z(), -p.y()}; }
const Eigen::Quaterniond world_to_gltf(Eigen::AngleAxisd(-EIGEN_PI / 2, Eigen::Vector3d::UnitX()));
// Body frame (forward +x, left +y, up +z) → glTF local (front +Z, up +Y, left +X): (x, y, z) → (y, z, x).
const Eigen::Quaterniond body_to_local = [] {
  Eigen::Matrix3d L;
  L << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  return Eigen::Quaterniond(L);
}();
// The node rotation that shows facing q: world_to_gltf · q · body_to_local⁻¹ (mesh vertices are body_to_local · v).
Eigen::Quaterniond node_rotation(const Eigen::Quaterniond& q) { return world_to_gltf * q * body_to_local.conjugate(); }
// The same map on coefficients (x, y, z, w): a product with fixed quaternions on either side is linear in q, so
// the animation's rotations (one per agent and frame) cost one 4×4 product instead of two quaternion products.
const Eigen::Matrix4d node_rotation_map = [] {
  Eigen::Matrix4d map;
  for (int k = 0; k < 4; ++k) {
    Eigen::Quaterniond unit;
    unit.coeffs() = Eigen::Vector4d::Unit(k);
    map.col(k) = node_rotation(unit).coeffs();
  }
  return map;
}();

std::size_t padded(std::size_t bytes) { return (bytes + 3) & ~std::size_t(3); }

// Text pieces appended in order: text as it is (it needs no escaping), counts and indices in decimal as
// nlohmann::json writes an unsigned integer.
void append_piece(std::string& text, const char* piece) { text += piece; }
void append_piece(std::string& text, std::size_t value) {
  char digits[24];
  const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
  text.append(digits, end);
}
template <class... Pieces>
void append_pieces(std::string& text, const Pieces&... pieces) {
  (append_piece(text, pieces), ...);
}

// For agents [n0, n1): the frames where each one's presence changes (frame 0 first), the keys of its STEP scale
// channel; empty for an agent present at every frame (no scale channel). Frame by frame over the agents, so the
// reads follow the positions' layout (one agent through every frame would stride a whole frame per read).
void presence_keys(const CrowdMotion& m, std::size_t n0, std::size_t n1, std::vector<std::vector<std::uint32_t>>& keys) {
  std::vector<unsigned char> before(n1 - n0), always(n1 - n0);
  for (std::size_t n = n0; n < n1; ++n) {
    keys[n].assign(1, 0);
    before[n - n0] = always[n - n0] = m.present(0, n);
  }
  for (std::size_t t = 1; t < m.frame_count(); ++t) {
    for (std::size_t n = n0; n < n1; ++n) {
      const unsigned char now = m.present(t, n);
      always[n - n0] &= now;
      if (now != before[n - n0]) keys[n].push_back(static_cast<std::uint32_t>(t));
      before[n - n0] = now;
    }
  }
  for (std::size_t n = n0; n < n1; ++n) {
    if (always[n - n0]) keys[n].clear();
  }
}

class GltfWriter {
 public:
  GltfWriter(const CrowdFile& crowd, detail::OutputFile& file, const ExportOptions& options)
      : crowd_(crowd), m_(crowd.motion), file_(file), options_(options) {}

  void write() {
    const std::size_t T = m_.frame_count(), N = m_.agent_count();
    if (T == 0 || N == 0) throw InputError("glTF export: the crowd has no frames or no agents, nothing to animate");
    keys_.resize(N);
    // Agent ranges in parallel, each agent's keys its own: the same keys either way.
    parallel_for(N, 256, [&](std::size_t n0, std::size_t n1) { presence_keys(m_, n0, n1, keys_); });
    const std::string json_text = document();
    const std::size_t json_size = padded(json_text.size());
    if (12 + 8 + json_size + 8 + bin_size_ > 0xFFFFFFFFu) {
      throw InputError("glTF export: " + std::to_string(N) + " agents × " + std::to_string(T) +
                       " frames need " + std::to_string((json_size + bin_size_) >> 20) +
                       " MiB, beyond a .glb's 4 GiB limit (export fewer frames or agents, or use usd)");
    }
    std::uint32_t header[5] = {glb_magic, 2, static_cast<std::uint32_t>(12 + 8 + json_size + 8 + bin_size_),
                               static_cast<std::uint32_t>(json_size), chunk_json};
    file_.write(header, sizeof header);
    file_.write(json_text);
    file_.write(std::string(json_size - json_text.size(), ' '));
    const std::uint32_t bin_header[2] = {static_cast<std::uint32_t>(bin_size_), chunk_bin};
    file_.write(bin_header, sizeof bin_header);
    binary();
  }

 private:
  // A JSON array built item by item as text, so a crowd of 10,000 agents costs its text (~1 kB per agent), not
  // a document tree ten times that.
  // A part of the list may be built on its own from the index its first item will have (count), and appended:
  // the text is the same as pushing its items one by one.
  struct JsonList {
    std::string text;
    std::size_t count = 0;
    std::size_t push(const json& item) {
      if (count) text += ',';
      text += item.dump();
      return count++;
    }
    // An item written as text by write(text): pieces, numbers and text that need no escaping.
    template <class Write>
    std::size_t push_text(Write write) {
      if (count) text += ',';
      write(text);
      return count++;
    }
    void append(const JsonList& part) {
      text += part.text;
      count = part.count;
    }
    [[nodiscard]] std::string array() const { return "[" + text + "]"; }
  };
  // The per-agent parts of the lists, for a range of agents.
  struct AgentLists {
    JsonList accessors, samplers, channels, nodes;
  };

  // The JSON document; fills the BIN layout (offsets and bin_size_) as it goes.
  std::string document() {
    const std::size_t T = m_.frame_count(), N = m_.agent_count();
    const detail::ProxyMesh& mesh = detail::proxy_mesh();
    JsonList accessors, views, nodes, samplers, channels;
    auto view = [&](std::size_t bytes, int target) {
      json v{{"buffer", 0}, {"byteOffset", bin_size_}, {"byteLength", bytes}};
      if (target) v["target"] = target;
      bin_size_ += padded(bytes);
      return views.push(v);
    };
    auto accessor = [&](std::size_t view_index, std::size_t offset, int type, std::size_t count, const char* shape,
                        const json& min = nullptr, const json& max = nullptr) {
      json a{{"bufferView", view_index}, {"byteOffset", offset}, {"componentType", type}, {"count", count}, {"type", shape}};
      if (!min.is_null()) a["min"] = min, a["max"] = max;
      return accessors.push(a);
    };
    // Frame times (an animation input states its bounds).
    const std::size_t times_view = view(T * 4, 0);
    const std::size_t times = accessor(times_view, 0, float_type, T, "SCALAR", json::array({0.0f}),
                                       json::array({static_cast<float>(m_.times.back() - m_.times.front())}));
    // Proxy mesh (POSITION states its bounds).
    const std::size_t positions_view = view(mesh.vertices.size() * 12, 34962);
    Eigen::AlignedBox3f box;
    for (const auto& v : mesh.vertices) box.extend(local_vertex(v));
    const std::size_t mesh_positions =
        accessor(positions_view, 0, float_type, mesh.vertices.size(), "VEC3", json::array({box.min().x(), box.min().y(), box.min().z()}),
                 json::array({box.max().x(), box.max().y(), box.max().z()}));
    const std::size_t indices_view = view(mesh.triangles.size() * 6, 34963);
    const std::size_t mesh_indices = accessor(indices_view, 0, ushort_type, mesh.triangles.size() * 3, "SCALAR");
    // Per-agent animation outputs, agent-major.
    const std::size_t outputs_view = view(N * T * 28, 0);
    // Agent ranges in parallel (their items are most of the document's text), each from the indices and key
    // offset its first agent's items take (prefix counts: 2 accessors, samplers and channels an agent, 2, 1 and 1
    // more with a scale channel), appended in range order: the text of one pass over the agents.
    std::vector<std::size_t> keyed_before(N + 1, 0), key_bytes_before(N + 1, 0);
    for (std::size_t n = 0; n < N; ++n) {
      keyed_before[n + 1] = keyed_before[n] + (keys_[n].empty() ? 0 : 1);
      key_bytes_before[n + 1] = key_bytes_before[n] + keys_[n].size() * 16;
    }
    const std::size_t keys_view = key_bytes_before[N] ? view(key_bytes_before[N], 0) : 0;
    detail::AgentPoses first(m_, options_.pose);  // each range asks its own agents' frame 0 only
    std::vector<AgentLists> parts(detail::agent_ranges);
    const std::size_t agent_accessors = accessors.count;
    detail::for_agent_ranges(N, [&](std::size_t r, std::size_t n0, std::size_t n1) {
      AgentLists& part = parts[r];
      part.accessors.count = agent_accessors + 2 * n0 + 2 * keyed_before[n0];
      part.samplers.count = part.channels.count = 2 * n0 + keyed_before[n0];
      part.nodes.count = n0;
      for (std::size_t n = n0; n < n1; ++n) agent_items(n, times, outputs_view, keys_view, key_bytes_before[n], first, part);
    });
    for (const AgentLists& part : parts) {
      accessors.append(part.accessors);
      samplers.append(part.samplers);
      channels.append(part.channels);
      nodes.append(part.nodes);
    }
    std::string node_list;
    for (std::size_t n = 0; n < N; ++n) node_list += (n ? "," : "") + std::to_string(n);
    json names = json::array(), props = json::array();
    for (const ActionKind& a : first.action_table()) {
      names.push_back(a.name);
      props.push_back(a.prop);
    }
    const json asset{{"version", "2.0"},
                     {"generator", "throng " + crowd_.provenance.program_version},
                     {"extras",
                      {{"throng",
                        {{"start_time_s", m_.times.front()}, {"credits", crowd_.provenance.credits}, {"action_names", names}, {"action_props", props}}}}}};
    const json meshes = json::array(
        {{{"name", "agent_proxy"}, {"primitives", json::array({{{"attributes", {{"POSITION", mesh_positions}}}, {"indices", mesh_indices}, {"mode", 4}}})}}});
    return "{\"asset\":" + asset.dump() + ",\"scene\":0,\"scenes\":[{\"name\":\"crowd\",\"nodes\":[" + node_list +
           "]}],\"nodes\":" + nodes.array() + ",\"meshes\":" + meshes.dump() +
           ",\"animations\":[{\"name\":\"crowd\",\"samplers\":" + samplers.array() + ",\"channels\":" + channels.array() +
           "}],\"accessors\":" + accessors.array() + ",\"bufferViews\":" + views.array() +
           ",\"buffers\":[{\"byteLength\":" + std::to_string(bin_size_) + "}]}";
  }

  // Agent n's items: its translation and rotation accessors, samplers and channels, its scale keys' (when it is
  // absent somewhere, at key_offset in the keys' view), and its node.
  void agent_items(std::size_t n, std::size_t times, std::size_t outputs_view, std::size_t keys_view, std::size_t key_offset,
                   detail::AgentPoses& first, AgentLists& out) const {
    const std::size_t T = m_.frame_count();
    auto accessor = [&](std::size_t view_index, std::size_t offset, std::size_t count, const char* shape, const json& min = nullptr,
                        const json& max = nullptr) {
      json a{{"bufferView", view_index}, {"byteOffset", offset}, {"componentType", float_type}, {"count", count}, {"type", shape}};
      if (!min.is_null()) a["min"] = min, a["max"] = max;
      return out.accessors.push(a);
    };
    // The items every agent has, written as text the way nlohmann::json dumps them (keys in its order, no spaces):
    // two thirds of the document's items, and building a tree for each took most of its 53 ms at 10,000 agents.
    auto float_accessor = [&](std::size_t offset, const char* shape) {
      return out.accessors.push_text([&](std::string& t) {
        append_pieces(t, "{\"bufferView\":", outputs_view, ",\"byteOffset\":", offset, ",\"componentType\":5126,\"count\":", T,
                      ",\"type\":\"", shape, "\"}");
      });
    };
    auto channel = [&](std::size_t input, std::size_t output, const char* interpolation, std::size_t node, const char* path) {
      const std::size_t sampler = out.samplers.push_text([&](std::string& t) {
        append_pieces(t, "{\"input\":", input, ",\"interpolation\":\"", interpolation, "\",\"output\":", output, "}");
      });
      out.channels.push_text([&](std::string& t) {
        append_pieces(t, "{\"sampler\":", sampler, ",\"target\":{\"node\":", node, ",\"path\":\"", path, "\"}}");
      });
    };
    static_assert(float_type == 5126);
    const std::size_t base = n * T * 28;
    const std::size_t translation = float_accessor(base, "VEC3");
    const std::size_t rotation = float_accessor(base + T * 12, "VEC4");
    const std::size_t node = n;
    channel(times, translation, "LINEAR", node, "translation");
    channel(times, rotation, "LINEAR", node, "rotation");
    const float r = static_cast<float>(m_.radii[n]);
    if (!keys_[n].empty()) {
      const std::size_t K = keys_[n].size();
      const std::size_t input = accessor(keys_view, key_offset, K, "SCALAR",
                                         json::array({static_cast<float>(m_.times[keys_[n].front()] - m_.times.front())}),
                                         json::array({static_cast<float>(m_.times[keys_[n].back()] - m_.times.front())}));
      const std::size_t output = accessor(keys_view, key_offset + K * 4, K, "VEC3");
      channel(input, output, "STEP", node, "scale");
    }
    const Eigen::Vector3d p = to_gltf(first.position(0, n));
    const Eigen::Quaterniond q = node_rotation(first.facing(0, n));
    const float s = m_.present(0, n) ? r : 0.0f;
    out.nodes.push({{"name", "agent_" + std::to_string(m_.ids[n])},
                    {"mesh", 0},
                    {"translation", {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())}},
                    {"rotation", {static_cast<float>(q.x()), static_cast<float>(q.y()), static_cast<float>(q.z()), static_cast<float>(q.w())}},
                    {"scale", {s, s, s}},
                    {"extras", {{"id", m_.ids[n]}, {"species", m_.species[n]}, {"radius", m_.radii[n]}}}});
  }

  static Eigen::Vector3f local_vertex(const Eigen::Vector3f& body) { return (body_to_local.cast<float>() * body); }

  void pad(std::size_t bytes) {
    static const char zeros[4] = {0, 0, 0, 0};
    file_.write(zeros, padded(bytes) - bytes);
  }

  void binary() {
    const std::size_t T = m_.frame_count(), N = m_.agent_count();
    std::vector<float> floats(T);
    for (std::size_t t = 0; t < T; ++t) floats[t] = static_cast<float>(m_.times[t] - m_.times.front());
    file_.write(floats.data(), T * 4);
    pad(T * 4);
    const detail::ProxyMesh& mesh = detail::proxy_mesh();
    for (const auto& v : mesh.vertices) {
      const Eigen::Vector3f l = local_vertex(v);
      file_.write(l.data(), 12);
    }
    for (const auto& tri : mesh.triangles) file_.write(tri.data(), 6);
    pad(mesh.triangles.size() * 6);
    // Agent groups: each agent's T translations then T rotations, filled frame by frame (each agent's frames in
    // order for the pose stream), written in one piece. Consecutive rotations share a hemisphere so LINEAR
    // interpolation (slerp, or Blender's component-wise blend) takes the short way.
    detail::AgentPoses poses(m_, options_.pose);
    const std::size_t per_agent = T * 7;
    const std::size_t group = std::max<std::size_t>(1, group_bytes / (per_agent * 4));
    // Groups are filled while the writer thread writes the group before (detail::BlockStream).
    detail::BlockStream<std::vector<float>> stream([&](std::vector<float>& buffer) { file_.write(buffer.data(), buffer.size() * 4); });
    std::vector<Eigen::Vector4d> previous;
    for (std::size_t n0 = 0; n0 < N; n0 += group) {
      const std::size_t G = std::min(group, N - n0);
      std::vector<float>& buffer = stream.next();
      buffer.resize(G * per_agent);
      previous.assign(G, Eigen::Vector4d::Zero());
      // Agent ranges in parallel, each walking every frame over its own agents (their positions at a frame are
      // contiguous); each agent's values land in its own slots, so the bytes do not depend on the thread count.
      detail::for_agent_ranges(G, [&](std::size_t, std::size_t j0, std::size_t j1) {
        std::vector<Eigen::Quaterniond> facing(j1 - j0);
        for (std::size_t t = 0; t < T; ++t) {
          poses.facings(t, n0 + j0, n0 + j1, facing.data());
          for (std::size_t j = j0; j < j1; ++j) {
            const Eigen::Vector3d p = to_gltf(poses.position(t, n0 + j));
            Eigen::Vector4d q = node_rotation_map * facing[j - j0].coeffs();
            if (q.dot(previous[j]) < 0) q = -q;  // previous is 0 at frame 0
            previous[j] = q;
            float* tr = buffer.data() + j * per_agent + t * 3;
            float* ro = buffer.data() + j * per_agent + T * 3 + t * 4;
            for (int k = 0; k < 3; ++k) tr[k] = static_cast<float>(p[k]);
            for (int k = 0; k < 4; ++k) ro[k] = static_cast<float>(q[k]);
          }
        }
      });
      stream.submit();
    }
    stream.finish();
    // Scale keys: STEP, 0 while absent.
    std::size_t written = 0;
    for (std::size_t n = 0; n < N; ++n) {
      const auto& keys = keys_[n];
      if (keys.empty()) continue;
      std::vector<float> data;
      for (const auto k : keys) data.push_back(static_cast<float>(m_.times[k] - m_.times.front()));
      const float r = static_cast<float>(m_.radii[n]);
      for (const auto k : keys) {
        const float s = m_.present(k, n) ? r : 0.0f;
        data.insert(data.end(), {s, s, s});
      }
      file_.write(data.data(), data.size() * 4);
      written += data.size() * 4;
    }
    pad(written);
  }

  const CrowdFile& crowd_;
  const CrowdMotion& m_;
  detail::OutputFile& file_;
  const ExportOptions& options_;
  std::vector<std::vector<std::uint32_t>> keys_;
  std::size_t bin_size_ = 0;
};

}  // namespace

void export_gltf(const CrowdFile& crowd, const std::filesystem::path& output, const ExportOptions& options) {
  detail::OutputFile file(output);
  GltfWriter(crowd, file, options).write();
  file.commit();
}

void export_gltf(const std::filesystem::path& crowd, const std::filesystem::path& output, const ExportOptions& options) {
  check_distinct(crowd, output);
  detail::OutputFile file(output);
  const CrowdFile data = read_crowd_file(crowd);
  GltfWriter(data, file, options).write();
  file.commit();
}

}  // namespace throng
