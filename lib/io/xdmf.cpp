#include "io/xdmf.hpp"

#include <fstream>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "io/atomic_file.hpp"

namespace hm::io {
namespace {

std::string dims_text(const std::vector<std::uint64_t>& dims) {
  return fmt::format("{}", fmt::join(dims, " "));
}

std::string data_item(const std::string& file, const std::string& dataset,
                      const std::vector<std::uint64_t>& dims, const char* number_type) {
  return fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"8\" "
      "Format=\"HDF\">{}:{}</DataItem>",
      dims_text(dims), number_type, file, dataset);
}

std::string field_xml(const XdmfField& f, const std::string& file) {
  std::vector<std::uint64_t> shown = f.dataset_dims;
  std::string item;
  if (f.slice >= 0) {
    HM_ASSERT(f.dataset_dims.size() == 3, "slices need a 3-D dataset ({})", f.dataset);
    shown = {f.dataset_dims[1], f.dataset_dims[2]};
    item = fmt::format(
        "<DataItem ItemType=\"HyperSlab\" Dimensions=\"{}\" Type=\"HyperSlab\">"
        "<DataItem Dimensions=\"3 3\" Format=\"XML\">{} 0 0 1 1 1 1 {} {}</DataItem>{}</DataItem>",
        dims_text(shown), f.slice, shown[0], shown[1],
        data_item(file, f.dataset, f.dataset_dims, "Float"));
  } else {
    item = data_item(file, f.dataset, f.dataset_dims, "Float");
  }
  const bool vector = shown.size() == 2 && shown[1] > 1;
  return fmt::format(
      "      <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">{}</Attribute>\n", f.name,
      vector ? "Vector" : "Scalar", f.on_nodes ? "Node" : "Cell", item);
}

}  // namespace

void write_xdmf(const std::filesystem::path& xdmf_path, const std::filesystem::path& h5_path,
                const std::vector<XdmfGrid>& grids) {
  const std::string file = h5_path.filename().string();
  std::string xml =
      "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      "<Xdmf Version=\"2.0\">\n  <Domain>\n";
  for (const auto& g : grids) {
    xml += fmt::format("    <Grid Name=\"{}\" GridType=\"Uniform\">\n", g.name);
    xml += fmt::format(
        "      <Topology TopologyType=\"{}\" NumberOfElements=\"{}\">{}</Topology>\n", g.topology,
        g.cells, data_item(file, g.cells_dataset, {g.cells, g.nodes_per_cell}, "Int"));
    xml += fmt::format(
        "      <Geometry GeometryType=\"{}\">{}</Geometry>\n", g.dim == 2 ? "XY" : "XYZ",
        data_item(file, g.nodes_dataset, {g.nodes, static_cast<std::uint64_t>(g.dim)}, "Float"));
    for (const auto& f : g.fields) xml += field_xml(f, file);
    xml += "    </Grid>\n";
  }
  xml += "  </Domain>\n</Xdmf>\n";
  AtomicOutput output(xdmf_path);
  {
    std::ofstream out(output.temp_path());
    out << xml;
    if (!out) input_error("cannot write '{}'", xdmf_path.string());
  }
  output.commit();
}

}  // namespace hm::io
