#include "agent_poses.h"
#include "frame_rate.h"
#include "half_number.h"
#include "frame_text.h"
#include "output_file.h"
#include "proxy_mesh.h"
#include "text_numbers.h"

#include <throng/io/export/usd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>

namespace throng {
namespace {

// A USD string literal: double-quoted, backslash escapes for \, " and line breaks.
std::string usd_string(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + '"';
}

// Species colours for the prototypes (displayColor), cycled.
constexpr std::array<std::array<float, 3>, 6> palette{{{0.85f, 0.33f, 0.10f}, {0.00f, 0.45f, 0.74f}, {0.47f, 0.67f, 0.19f},
                                                      {0.49f, 0.18f, 0.56f}, {0.93f, 0.69f, 0.13f}, {0.30f, 0.75f, 0.93f}}};

struct TimeCodes {
  double per_second = 24.0;  // USD's default for a one-frame crowd
  std::vector<double> codes;
  bool uniform = false;
};

TimeCodes time_codes(const std::vector<double>& times) {
  TimeCodes c;
  const std::size_t T = times.size();
  if (const auto fps = detail::uniform_frame_rate(times)) {
    c.per_second = *fps;
    c.uniform = true;
    for (std::size_t k = 0; k < T; ++k) c.codes.push_back(static_cast<double>(k));
    return c;
  }
  if (T >= 2) c.per_second = static_cast<double>(T - 1) / (times.back() - times.front());
  for (std::size_t k = 0; k < T; ++k) c.codes.push_back((times[k] - times.front()) * c.per_second);
  return c;
}

// A tuple's opening, "(" for the first agent and ", (" after: characters put one by one (a text picked at run
// time would be a copy call of its length, twice for every agent and frame).
char* open_tuple(char* out, std::size_t agent) {
  if (agent) *out++ = ',', *out++ = ' ';
  *out++ = '(';
  return out;
}

class UsdWriter {
 public:
  UsdWriter(const CrowdFile& crowd, detail::OutputFile& file, const ExportOptions& options)
      : crowd_(crowd), m_(crowd.motion), file_(file), options_(options), clock_(time_codes(m_.times)) {}

  void write() {
    header();
    text_ += "def Xform \"Crowd\"\n{\n    def PointInstancer \"Agents\"\n    {\n";
    constant_attributes();
    time_samples("point3f[] positions", 40, [&](detail::AgentPoses& poses, std::size_t t, std::size_t n, detail::TextBuffer& out) {
      const Eigen::Vector3d p = poses.position(t, n);
      char* c = out.room(8 + 3 * detail::max_number_chars);
      c = open_tuple(c, n);
      c = detail::put_number(c, static_cast<float>(p.x()));
      c = detail::put_text(c, ", ");
      c = detail::put_number(c, static_cast<float>(p.y()));
      c = detail::put_text(c, ", ");
      c = detail::put_number(c, static_cast<float>(p.z()));
      *c++ = ')';
      out.advance(c);
    });
    // A frame's facings a range of agents at a time (AgentPoses::facings), each range into its own agents' slots.
    std::vector<Eigen::Quaterniond> facing(m_.agent_count());
    time_samples(
        "quath[] orientations", 32,
        [&](detail::AgentPoses&, std::size_t, std::size_t n, detail::TextBuffer& out) {
          const Eigen::Quaterniond& q = facing[n];
          char* c = out.room(12 + 4 * detail::max_number_chars);
          c = open_tuple(c, n);
          c = detail::put_half(c, q.w());
          c = detail::put_text(c, ", ");
          c = detail::put_half(c, q.x());
          c = detail::put_text(c, ", ");
          c = detail::put_half(c, q.y());
          c = detail::put_text(c, ", ");
          c = detail::put_half(c, q.z());
          *c++ = ')';
          out.advance(c);
        },
        [](std::size_t, detail::TextBuffer&) {},
        [&](detail::AgentPoses& poses, std::size_t t, std::size_t n0, std::size_t n1) { poses.facings(t, n0, n1, facing.data() + n0); });
    // The ids of the absent agents: few, listed by the frame's head (one pass over presence, no per-agent text).
    time_samples(
        "int64[] invisibleIds", 0, [](detail::AgentPoses&, std::size_t, std::size_t, detail::TextBuffer&) {},
        [&](std::size_t t, detail::TextBuffer& out) {
          bool first = true;
          for (std::size_t n = 0; n < m_.agent_count(); ++n) {
            if (m_.present(t, n)) continue;
            char* c = out.room(2 + detail::max_number_chars);
            if (!first) c = detail::put_text(c, ", ");
            first = false;
            out.advance(detail::put_number(c, m_.ids[n]));
          }
        });
    write_text("        int[] primvars:throng:action (\n            interpolation = \"vertex\"\n        )\n");
    time_samples("int[] primvars:throng:action", 4, [&](detail::AgentPoses& poses, std::size_t t, std::size_t n, detail::TextBuffer& out) {
      char* c = out.room(2 + detail::max_number_chars);
      if (n) c = detail::put_text(c, ", ");
      // An absent agent is invisible; its stored action is −1 (none), written as the table's first entry.
      out.advance(detail::put_number(c, std::max(poses.action(t, n), std::int32_t{0})));
    });
    prototypes();
    text_ += "    }\n}\n";
    file_.write(text_);
  }

 private:
  void write_text(const std::string& text) {
    text_ += text;
    file_.write(text_);
    text_.clear();
  }

  void header() {
    const std::size_t T = m_.frame_count();
    text_ += "#usda 1.0\n(\n    customLayerData = {\n";
    std::string credits;
    for (const auto& c : crowd_.provenance.credits) credits += (credits.empty() ? "" : "; ") + c;
    text_ += "        string \"throng:credits\" = " + usd_string(credits) + "\n";
    text_ += "        double \"throng:startTime\" = ";
    detail::append_number(text_, T ? m_.times.front() : 0.0);
    text_ += "\n    }\n    defaultPrim = \"Crowd\"\n";
    text_ += "    doc = \"A crowd exported by throng: one PointInstancer, an instance per agent\"\n";
    text_ += "    endTimeCode = ";
    detail::append_number(text_, T ? clock_.codes.back() : 0.0);
    text_ += "\n    framesPerSecond = ";
    detail::append_number(text_, clock_.per_second);
    text_ += "\n    metersPerUnit = 1\n    startTimeCode = 0\n    timeCodesPerSecond = ";
    detail::append_number(text_, clock_.per_second);
    text_ += "\n    upAxis = \"Z\"\n)\n\n";
  }

  void constant_attributes() {
    const std::size_t N = m_.agent_count();
    for (std::size_t n = 0; n < N; ++n) species_.emplace(m_.species[n], 0);
    int index = 0;
    for (auto& [s, i] : species_) i = index++;
    text_ += "        int64[] ids = [";
    for (std::size_t n = 0; n < N; ++n) {
      if (n) text_ += ", ";
      detail::append_number(text_, m_.ids[n]);
    }
    text_ += "]\n        int[] protoIndices = [";
    for (std::size_t n = 0; n < N; ++n) {
      if (n) text_ += ", ";
      detail::append_number(text_, species_.at(m_.species[n]));
    }
    text_ += "]\n        rel prototypes = [";
    for (const auto& [s, i] : species_) {
      text_ += i ? ", " : "";
      text_ += "</Crowd/Agents/Prototypes/" + prototype_name(s) + ">";
    }
    text_ += "]\n        float3[] scales = [";
    for (std::size_t n = 0; n < N; ++n) {
      const float r = static_cast<float>(m_.radii[n]);
      text_ += n ? ", (" : "(";
      for (int k = 0; k < 3; ++k) {
        if (k) text_ += ", ";
        detail::append_number(text_, r);
      }
      text_ += ')';
    }
    text_ += "]\n        int[] primvars:throng:species = [";
    for (std::size_t n = 0; n < N; ++n) {
      if (n) text_ += ", ";
      detail::append_number(text_, m_.species[n]);
    }
    text_ += "] (\n            interpolation = \"vertex\"\n        )\n";
    detail::AgentPoses poses(m_, options_.pose);
    std::string names, props;
    for (const ActionKind& a : poses.action_table()) {
      names += (names.empty() ? "" : ", ") + usd_string(a.name);
      props += (props.empty() ? "" : ", ") + usd_string(a.prop);
    }
    text_ += "        custom uniform string[] throng:actionNames = [" + names + "]\n";
    text_ += "        custom uniform string[] throng:actionProps = [" + props + "]\n";
  }

  // `declaration`.timeSamples = { code: [values], ... }, one line per frame, streamed (detail::stream_frame_text):
  // item(poses, t, n, out) writes agent n's value at frame t (its own separator first), in parallel over agent
  // ranges, each pass with its own pose stream; head(t, out) may write the frame's values itself.
  // before(poses, t, n0, n1) runs before a range's items of frame t (detail::stream_frame_text).
  template <class Item, class Head = void (*)(std::size_t, detail::TextBuffer&),
            class Before = void (*)(detail::AgentPoses&, std::size_t, std::size_t, std::size_t)>
  void time_samples(const std::string& declaration, std::size_t bytes_per_agent, Item item,
                    Head head = [](std::size_t, detail::TextBuffer&) {},
                    Before before = [](detail::AgentPoses&, std::size_t, std::size_t, std::size_t) {}) {
    detail::AgentPoses poses(m_, options_.pose);
    write_text("        " + declaration + ".timeSamples = {\n");
    detail::stream_frame_text(
        file_, m_.frame_count(), m_.agent_count(), {.bytes_per_agent = std::max<std::size_t>(bytes_per_agent, 1)},
        [&](std::size_t t, detail::TextBuffer& out) {
          out.append("            ");
          out.advance(detail::put_number(out.room(detail::max_number_chars), clock_.codes[t]));
          out.append(": [");
          head(t, out);
        },
        [&](std::size_t t, std::size_t n, detail::TextBuffer& out) { item(poses, t, n, out); },
        [](std::size_t, detail::TextBuffer& out) { out.append("],\n"); },
        [&](std::size_t t, std::size_t n0, std::size_t n1) { before(poses, t, n0, n1); });
    text_ += "        }\n";
  }

  static std::string prototype_name(std::int32_t species) {
    return species < 0 ? "species_minus_" + std::to_string(-static_cast<std::int64_t>(species)) : "species_" + std::to_string(species);
  }

  void prototypes() {
    const detail::ProxyMesh& mesh = detail::proxy_mesh();
    text_ += "\n        def Scope \"Prototypes\"\n        {\n";
    for (const auto& [s, i] : species_) {
      text_ += "            def Mesh \"" + prototype_name(s) + "\"\n            {\n";
      Eigen::AlignedBox3f box;
      for (const auto& v : mesh.vertices) box.extend(v);
      text_ += "                float3[] extent = [";
      for (const Eigen::Vector3f& corner : {box.min(), box.max()}) {
        text_ += corner == box.min() ? "(" : ", (";
        for (int k = 0; k < 3; ++k) {
          if (k) text_ += ", ";
          detail::append_number(text_, corner[k]);
        }
        text_ += ')';
      }
      text_ += "]\n                int[] faceVertexCounts = [";
      for (std::size_t f = 0; f < mesh.triangles.size(); ++f) text_ += f ? ", 3" : "3";
      text_ += "]\n                int[] faceVertexIndices = [";
      for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
        for (int k = 0; k < 3; ++k) {
          if (f || k) text_ += ", ";
          detail::append_number(text_, static_cast<int>(mesh.triangles[f][static_cast<std::size_t>(k)]));
        }
      }
      text_ += "]\n                point3f[] points = [";
      for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        text_ += v ? ", (" : "(";
        for (int k = 0; k < 3; ++k) {
          if (k) text_ += ", ";
          detail::append_number(text_, mesh.vertices[v][k]);
        }
        text_ += ')';
      }
      const auto& colour = palette[static_cast<std::size_t>(i) % palette.size()];
      text_ += "]\n                color3f[] primvars:displayColor = [(";
      for (int k = 0; k < 3; ++k) {
        if (k) text_ += ", ";
        detail::append_number(text_, colour[static_cast<std::size_t>(k)]);
      }
      text_ += ")]\n                uniform token subdivisionScheme = \"none\"\n            }\n";
    }
    text_ += "        }\n";
  }

  const CrowdFile& crowd_;
  const CrowdMotion& m_;
  detail::OutputFile& file_;
  const ExportOptions& options_;
  TimeCodes clock_;
  std::map<std::int32_t, int> species_;  // species → prototype index, in increasing species order
  std::string text_;
};

}  // namespace

void export_usd(const CrowdFile& crowd, const std::filesystem::path& output, const ExportOptions& options) {
  detail::OutputFile file(output);
  UsdWriter(crowd, file, options).write();
  file.commit();
}

void export_usd(const std::filesystem::path& crowd, const std::filesystem::path& output, const ExportOptions& options) {
  check_distinct(crowd, output);
  detail::OutputFile file(output);
  const CrowdFile data = read_crowd_file(crowd);
  UsdWriter(data, file, options).write();
  file.commit();
}

}  // namespace throng
