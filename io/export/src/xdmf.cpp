#include "output_file.h"
#include "text_numbers.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/export/xdmf.h>
#include <throng/io/hdf5.h>

#include <hdf5.h>

#include <string>
#include <vector>

namespace throng {
namespace {

// The dimensions of dataset `name` below `group` (InputError when missing).
std::vector<std::uint64_t> dimensions(const h5::Group& group, const std::string& name) {
  if (!group.has(name)) throw InputError(group.where(name) + ": missing dataset");
  h5::Handle dataset(H5Dopen2(group.id(), name.c_str(), H5P_DEFAULT));
  h5::Handle space(H5Dget_space(dataset.id()));
  const int rank = H5Sget_simple_extent_ndims(space.id());
  if (!dataset.valid() || rank < 0) throw InputError(group.where(name) + ": cannot be read as a dataset");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
  return {dims.begin(), dims.end()};
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

struct Layout {
  std::uint64_t frames = 0, agents = 0;
  std::vector<double> times;
  bool radius = false, species = false, orientation = false, action = false;
};

Layout read_layout(const std::filesystem::path& crowd) {
  const h5::File f = h5::File::open(crowd);
  const h5::Group root = f.root();
  if (!root.has("h5md")) throw InputError(root.where("h5md") + ": missing group; not an H5MD crowd file");
  const h5::Group trajectory = root.open_group("particles/trajectory");
  Layout l;
  const auto position = dimensions(trajectory, "position/value");
  if (position.size() != 3 || position[2] != 3) throw InputError(trajectory.where("position/value") + ": expected shape [frames][agents][3]");
  l.frames = position[0];
  l.agents = position[1];
  l.times = trajectory.read_doubles("position/time", 1).values;
  if (l.times.size() != l.frames) throw InputError(trajectory.where("position/time") + ": one time per frame of position/value expected");
  if (dimensions(trajectory, "id/value") != std::vector<std::uint64_t>{l.frames, l.agents}) {
    throw InputError(trajectory.where("id/value") + ": expected shape [frames][agents]");
  }
  l.radius = root.has("parameters/throng/agents/radius") &&
             dimensions(root, "parameters/throng/agents/radius") == std::vector<std::uint64_t>{l.agents};
  l.species = trajectory.has("species") && dimensions(trajectory, "species") == std::vector<std::uint64_t>{l.agents};
  l.orientation = trajectory.has_group("orientation") &&
                  trajectory.open_group("orientation").has_attribute("components") &&
                  dimensions(trajectory, "orientation/value") == std::vector<std::uint64_t>{l.frames, l.agents, 4};
  l.action = trajectory.has_group("action") && dimensions(trajectory, "action/value") == std::vector<std::uint64_t>{l.frames, l.agents};
  return l;
}

class XdmfWriter {
 public:
  XdmfWriter(const Layout& layout, std::string h5) : l_(layout), h5_(std::move(h5)) {}

  std::string document() {
    out_ = "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
    out_ += "  <Grid Name=\"crowd\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::uint64_t t = 0; t < l_.frames; ++t) frame(t);
    out_ += "  </Grid>\n </Domain>\n</Xdmf>\n";
    return std::move(out_);
  }

 private:
  // The frame-t slice [t][0..N)[0..width) of a [T][N](width) dataset.
  void slab(std::uint64_t t, const std::string& dataset, const char* number, int precision, std::uint64_t width, const std::string& indent) {
    const std::string N = std::to_string(l_.agents), T = std::to_string(l_.frames), w = std::to_string(width);
    const bool vector = width > 1;
    out_ += indent + "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" + N + (vector ? " " + w : "") + "\">\n";
    out_ += indent + " <DataItem Dimensions=\"3 " + (vector ? "3" : "2") + "\" Format=\"XML\">" + std::to_string(t) +
            (vector ? " 0 0 1 1 1 1 " + N + " " + w : " 0 1 1 1 " + N) + "</DataItem>\n";
    out_ += indent + " <DataItem Dimensions=\"" + T + " " + N + (vector ? " " + w : "") + "\" NumberType=\"" + number +
            "\" Precision=\"" + std::to_string(precision) + "\" Format=\"HDF\">" + h5_ + ":" + dataset + "</DataItem>\n";
    out_ += indent + "</DataItem>\n";
  }

  // Component c of the frame-t orientation: the slice [t][0..N)[c].
  void component(std::uint64_t t, int c, const std::string& indent) {
    const std::string N = std::to_string(l_.agents), T = std::to_string(l_.frames);
    out_ += indent + "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" + N + " 1\">\n";
    out_ += indent + " <DataItem Dimensions=\"3 3\" Format=\"XML\">" + std::to_string(t) + " 0 " + std::to_string(c) +
            " 1 1 1 1 " + N + " 1</DataItem>\n";
    out_ += indent + " <DataItem Dimensions=\"" + T + " " + N + " 4\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5_ +
            ":/particles/trajectory/orientation/value</DataItem>\n";
    out_ += indent + "</DataItem>\n";
  }

  void attribute_head(const char* name, const char* type) {
    out_ += "    <Attribute Name=\"" + std::string(name) + "\" AttributeType=\"" + type + "\" Center=\"Node\">\n";
  }

  void frame(std::uint64_t t) {
    const std::string N = std::to_string(l_.agents);
    out_ += "   <Grid Name=\"frame " + std::to_string(t) + "\" GridType=\"Uniform\">\n    <Time Value=\"";
    detail::append_number(out_, l_.times[t]);
    out_ += "\"/>\n    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + N + "\" NodesPerElement=\"1\"/>\n";
    out_ += "    <Geometry GeometryType=\"XYZ\">\n";
    slab(t, "/particles/trajectory/position/value", "Float", 8, 3, "     ");
    out_ += "    </Geometry>\n";
    attribute_head("id", "Scalar");
    slab(t, "/particles/trajectory/id/value", "Int", 8, 1, "     ");
    out_ += "    </Attribute>\n";
    if (l_.radius) {
      attribute_head("radius", "Scalar");
      out_ += "     <DataItem Dimensions=\"" + N + "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5_ +
              ":/parameters/throng/agents/radius</DataItem>\n    </Attribute>\n";
    }
    if (l_.species) {
      attribute_head("species", "Scalar");
      out_ += "     <DataItem Dimensions=\"" + N + "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" + h5_ +
              ":/particles/trajectory/species</DataItem>\n    </Attribute>\n";
    }
    if (l_.orientation) {
      attribute_head("orientation", "Matrix");
      slab(t, "/particles/trajectory/orientation/value", "Float", 8, 4, "     ");
      out_ += "    </Attribute>\n";
      // facing = q · (1, 0, 0) = (1 − 2(y² + z²), 2(xy + wz), 2(xz − wy)) from the components $0..$3 = x, y, z, w.
      // Written with + and negative constants only: ParaView 5.11's XDMF reader evaluates a − b as b − a, and
      // its JOIN of expressions reads garbage, so each component is a Function of its own, joined.
      attribute_head("facing", "Vector");
      out_ += "     <DataItem ItemType=\"Function\" Dimensions=\"" + N + " 3\" Function=\"JOIN($0, $1, $2)\">\n";
      for (const char* expression : {"1 + -2 * ($1 * $1 + $2 * $2)", "2 * ($0 * $1 + $3 * $2)", "2 * ($0 * $2 + -1 * $3 * $1)"}) {
        out_ += "      <DataItem ItemType=\"Function\" Dimensions=\"" + N + " 1\" Function=\"" + expression + "\">\n";
        for (int c = 0; c < 4; ++c) component(t, c, "       ");
        out_ += "      </DataItem>\n";
      }
      out_ += "     </DataItem>\n    </Attribute>\n";
    }
    if (l_.action) {
      attribute_head("action", "Scalar");
      slab(t, "/particles/trajectory/action/value", "Int", 4, 1, "     ");
      out_ += "    </Attribute>\n";
    }
    out_ += "   </Grid>\n";
  }

  const Layout& l_;
  std::string h5_;
  std::string out_;
};

}  // namespace

CrowdShape export_xdmf(const std::filesystem::path& crowd, const std::filesystem::path& output) {
  check_distinct(crowd, output);
  detail::OutputFile file(output);
  const Layout layout = read_layout(crowd);
  std::filesystem::path folder = output.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  std::filesystem::path reference = std::filesystem::relative(std::filesystem::absolute(crowd), std::filesystem::absolute(folder), ec);
  if (ec || reference.empty()) reference = std::filesystem::absolute(crowd);
  file.write(XdmfWriter(layout, xml_escape(reference.string())).document());
  file.commit();
  return {.frames = static_cast<std::size_t>(layout.frames), .agents = static_cast<std::size_t>(layout.agents)};
}

}  // namespace throng
