#include "server/io/xdmf_writer.h"

#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>

#include "server/io/text_output.h"

namespace cascade {
namespace {

const char* number_type_name(XdmfWriter::NumberType type) {
  switch (type) {
    case XdmfWriter::NumberType::uint8:
      return "UChar";
    case XdmfWriter::NumberType::uint32:
      return "UInt";
    case XdmfWriter::NumberType::float64:
      break;
  }
  return "Float";
}

int precision_bytes(XdmfWriter::NumberType type) {
  switch (type) {
    case XdmfWriter::NumberType::uint8:
      return 1;
    case XdmfWriter::NumberType::uint32:
      return 4;
    case XdmfWriter::NumberType::float64:
      break;
  }
  return 8;
}

// Six-component fields (symmetric tensors in FieldFrame's Voigt order xx, yy, zz, xy, yz, zx) are
// "Matrix", not "Tensor6": XDMF's Tensor6 means the order xx, xy, xz, yy, yz, zz, and ParaView's
// legacy XDMF Reader expands a Tensor6 to 3 x 3 in that order, which would silently scramble ours
// (it reads any Matrix as one component, an array it flags as too long: wrong, but visibly so).
// The Xdmf3 readers pass either type through as a 6-component array unchanged, and ParaView reads
// a 6-component array as a symmetric tensor XX, YY, ZZ, XY, YZ, XZ: our order (docs/output.md).
const char* attribute_type(int components) {
  switch (components) {
    case 1:
      return "Scalar";
    case 3:
      return "Vector";
    case 9:
      return "Tensor";
    default:
      return "Matrix";
  }
}

}  // namespace

// A sidecar left by an earlier run in the same place would name frames that the new HDF5 file does
// not hold (it is truncated): it goes, and the first frame writes the new one.
XdmfWriter::XdmfWriter(std::filesystem::path xdmf_path, std::string h5_file_name)
    : path_(std::move(xdmf_path)), h5_file_name_(std::move(h5_file_name)) {
  std::error_code ignored;  // none there, or one that cannot go: the first frame replaces it
  std::filesystem::remove(path_, ignored);
}

std::string XdmfWriter::data_item(const std::string& dimensions, NumberType type,
                                  const std::string& dataset) const {
  return "<DataItem Dimensions=\"" + dimensions + "\" NumberType=\"" + number_type_name(type) +
         "\" Precision=\"" + std::to_string(precision_bytes(type)) + "\" Format=\"HDF\">" +
         xml_escape(h5_file_name_ + ":" + dataset) + "</DataItem>";
}

void XdmfWriter::append(const Grid& grid) {
  const std::string n = std::to_string(grid.nodes);
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu", grid_count_);
  std::string x = std::string("      <Grid Name=\"") + name + "\" GridType=\"Uniform\">\n";
  x += "        <Time Value=\"" + format_double(grid.time) + "\"/>\n";
  // Explicit connectivity: both ParaView readers then make one vertex cell per particle.
  x += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
       "\" NodesPerElement=\"1\">\n          " +
       data_item(n, NumberType::uint32, grid.connectivity_dataset) + "\n        </Topology>\n";
  x += "        <Geometry GeometryType=\"XYZ\">\n          " +
       data_item(n + " 3", NumberType::float64, grid.position_dataset) + "\n        </Geometry>\n";
  for (const Attribute& a : grid.attributes) {
    const std::string dims = a.components == 1 ? n : n + " " + std::to_string(a.components);
    x += "        <Attribute Name=\"" + xml_escape(a.name) + "\" AttributeType=\"" +
         attribute_type(a.components) + "\" Center=\"Node\">\n          " +
         data_item(dims, a.type, a.dataset) + "\n        </Attribute>\n";
  }
  x += "      </Grid>\n";

  write_file_atomically(path_,
                        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
                        "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
                        "  <Domain>\n"
                        "    <Grid Name=\"particles\" GridType=\"Collection\" "
                        "CollectionType=\"Temporal\">\n" +
                            grids_ + x +
                            "    </Grid>\n"
                            "  </Domain>\n"
                            "</Xdmf>\n");
  grids_ += x;  // only once the file holding it is in place
  ++grid_count_;
}

}  // namespace cascade
