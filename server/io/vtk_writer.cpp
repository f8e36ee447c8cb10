#include "server/io/vtk_writer.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "server/io/text_output.h"

namespace cascade {
namespace {

// Component names of 6-component (symmetric tensor) arrays, in FieldFrame's Voigt order: the
// order ParaView assumes for a 6-component tensor (XX, YY, ZZ, XY, YZ, XZ).
constexpr const char* kVoigtComponents[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};

template <typename Array, typename Value>
void fill(Array* array, const char* name, int components, const std::vector<Value>& values) {
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
}

void check_sizes(const FieldFrame& frame) {
  const std::size_t n = frame.size();
  if (frame.position.size() != 3 * n || frame.phase.size() != n)
    throw std::invalid_argument("position or phase size does not match " + std::to_string(n) +
                                " particles");
  if (!frame.free_surface.empty() && frame.free_surface.size() != n)
    throw std::invalid_argument("free_surface has " + std::to_string(frame.free_surface.size()) +
                                " values, expected " + std::to_string(n) + " or none");
  for (const FieldFrame::RealField& f : frame.fields)
    if (f.components < 1 || f.values.size() != n * static_cast<std::size_t>(f.components))
      throw std::invalid_argument("field '" + f.name + "' has " + std::to_string(f.values.size()) +
                                  " values, expected " + std::to_string(f.components) + " x " +
                                  std::to_string(n));
}

}  // namespace

VtkSeriesWriter::VtkSeriesWriter(std::filesystem::path directory, VtkWriterOptions options)
    : directory_(std::move(directory)), options_(options) {
  std::filesystem::create_directories(directory_);
}

std::filesystem::path VtkSeriesWriter::write(const FieldFrame& frame) {
  check_sizes(frame);
  const std::size_t n = frame.size();

  vtkNew<vtkDoubleArray> coordinates;
  fill(coordinates.GetPointer(), "position", 3, frame.position);
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);

  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfTuples(static_cast<vtkIdType>(n));
  std::iota(connectivity->GetPointer(0), connectivity->GetPointer(0) + n, vtkIdType{0});
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(1, connectivity);

  vtkNew<vtkPolyData> polydata;
  polydata->SetPoints(points);
  polydata->SetVerts(vertices);

  vtkPointData* point_data = polydata->GetPointData();
  vtkNew<vtkUnsignedCharArray> phase;
  fill(phase.GetPointer(), "phase", 1, frame.phase);
  point_data->AddArray(phase);
  vtkNew<vtkUnsignedIntArray> id;
  fill(id.GetPointer(), "id", 1, frame.id);
  point_data->AddArray(id);
  if (!frame.free_surface.empty()) {
    vtkNew<vtkUnsignedCharArray> free_surface;
    fill(free_surface.GetPointer(), "free_surface", 1, frame.free_surface);
    point_data->AddArray(free_surface);
  }
  for (const FieldFrame::RealField& f : frame.fields) {
    vtkNew<vtkDoubleArray> array;
    fill(array.GetPointer(), f.name.c_str(), f.components, f.values);
    if (f.components == 6)
      for (int c = 0; c < 6; ++c) array->SetComponentName(c, kVoigtComponents[c]);
    point_data->AddArray(array);
  }

  // ParaView reads the time of a lone .vtp file from this field-data array.
  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->InsertNextValue(frame.time);
  polydata->GetFieldData()->AddArray(time);

  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu.vtp", entries_.size());
  const std::filesystem::path path = directory_ / name;
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(polydata);
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary, not base64
  writer->SetHeaderTypeToUInt64();  // arrays over 4 GiB
  if (options_.compress)
    writer->SetCompressorTypeToZLib();
  else
    writer->SetCompressorTypeToNone();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw std::runtime_error("VTK: cannot write " + path.string());

  const std::string entry = "    <DataSet timestep=\"" + format_double(frame.time) +
                            "\" group=\"\" part=\"0\" file=\"" + xml_escape(name) + "\"/>\n";
  std::string pvd =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const std::string& earlier : entries_) pvd += earlier;
  pvd += entry + "  </Collection>\n</VTKFile>\n";
  write_file_atomically(pvd_path(), pvd);
  entries_.push_back(entry);
  return path;
}

}  // namespace cascade
