#include "vtk_io.hpp"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <mutex>

#include "markup_checks.hpp"
#include "partreg/core/errors.hpp"
#include "partreg/io/read_limits.hpp"

namespace partreg::io::detail {
namespace {

// VTK prints warnings in its own windows or on stderr; partreg reports failures itself.
void silence_vtk() {
  static std::once_flag once;
  std::call_once(once, [] { vtkObject::GlobalWarningDisplayOff(); });
}

bool is_integer_array(vtkDataArray& array) {
  const int type = array.GetDataType();
  return type == VTK_CHAR || type == VTK_SIGNED_CHAR || type == VTK_UNSIGNED_CHAR || type == VTK_SHORT ||
         type == VTK_UNSIGNED_SHORT || type == VTK_INT;
}

// Triangles of every polygon cell (fanned), each index checked against the points.
core::Faces triangles(vtkPolyData& poly, const std::string& file) {
  std::vector<Eigen::Vector3i> faces;
  vtkCellArray* polys = poly.GetPolys();
  const vtkIdType points = poly.GetNumberOfPoints();
  vtkNew<vtkIdList> cell;
  for (polys->InitTraversal(); polys->GetNextCell(cell);) {
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
      if (cell->GetId(k) < 0 || cell->GetId(k) >= points)
        throw InputError(file + ": a polygon refers to point " + std::to_string(cell->GetId(k)) + " of " +
                         std::to_string(points));
    for (vtkIdType k = 2; k < cell->GetNumberOfIds(); ++k)
      faces.emplace_back(static_cast<int>(cell->GetId(0)), static_cast<int>(cell->GetId(k - 1)),
                         static_cast<int>(cell->GetId(k)));
    check_count(file, "faces", faces.size(), kReadBudget.max_faces);
  }
  core::Faces result(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) result.row(static_cast<Eigen::Index>(f)) = faces[f];
  return result;
}

void read_point_arrays(vtkPolyData& poly, PolyData& data) {
  vtkPointData* arrays = poly.GetPointData();
  const vtkIdType n = poly.GetNumberOfPoints();
  vtkDataArray* normals = arrays->GetNormals();
  if (normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == n) {
    data.normals.resize(n, 3);
    for (vtkIdType i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) data.normals(i, d) = normals->GetComponent(i, d);
  }
  for (int a = 0; a < arrays->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = arrays->GetArray(a);
    if (!array || array == normals || !array->GetName() || array->GetNumberOfComponents() != 1 ||
        array->GetNumberOfTuples() != n)
      continue;
    Eigen::VectorXd values(n);
    for (vtkIdType i = 0; i < n; ++i) values[i] = array->GetComponent(i, 0);
    if (is_integer_array(*array))
      data.attributes.integers[array->GetName()] = values.cast<int>();
    else
      data.attributes.reals[array->GetName()] = values;
  }
}

}  // namespace

PolyData read_vtp(const std::filesystem::path& path) {
  silence_vtk();
  const std::string file = path.string();
  checked_input_size(path);
  check_vtp(path);  // nesting and declared counts, before VTK's recursive parser allocates
  vtkNew<vtkXMLPolyDataReader> reader;
  if (!reader->CanReadFile(file.c_str())) throw InputError(file + " is not a VTK PolyData (.vtp) file");
  reader->SetFileName(file.c_str());
  try {
    reader->Update();
  } catch (const std::bad_alloc&) {
    throw InputError(file + ": VTK ran out of memory reading it (counts larger than the file holds?)");
  }
  vtkPolyData* poly = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || !poly || !poly->GetPoints())
    throw InputError("cannot read VTK PolyData file " + file);
  const vtkIdType n = poly->GetNumberOfPoints();
  check_count(file, "points", static_cast<std::uint64_t>(n), kReadBudget.max_points);
  PolyData data;
  data.points.resize(n, 3);
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    poly->GetPoint(i, p);
    data.points.row(i) << p[0], p[1], p[2];
  }
  data.faces = triangles(*poly, file);
  read_point_arrays(*poly, data);
  auto* names = vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("part_names"));
  if (names && names->GetNumberOfComponents() == 1) {
    check_count(file, "part names", static_cast<std::uint64_t>(names->GetNumberOfValues()),
                kReadBudget.max_points);
    for (vtkIdType p = 0; p < names->GetNumberOfValues(); ++p)
      data.attributes.part_names.push_back(names->GetValue(p));
  }
  return data;
}

void write_vtp(std::ostream& out, const PolyData& data) {
  silence_vtk();
  const auto n = static_cast<vtkIdType>(data.points.rows());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i) points->SetPoint(i, data.points(i, 0), data.points(i, 1), data.points(i, 2));
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  vtkNew<vtkCellArray> cells;
  if (data.faces.rows() > 0) {
    for (Eigen::Index f = 0; f < data.faces.rows(); ++f) {
      const vtkIdType ids[3] = {data.faces(f, 0), data.faces(f, 1), data.faces(f, 2)};
      cells->InsertNextCell(3, ids);
    }
    poly->SetPolys(cells);
  } else {
    for (vtkIdType i = 0; i < n; ++i) cells->InsertNextCell(1, &i);
    poly->SetVerts(cells);
  }
  if (data.normals.rows() == n && n > 0) {
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) normals->SetComponent(i, d, data.normals(i, d));
    poly->GetPointData()->SetNormals(normals);
  }
  for (const auto& [name, values] : data.attributes.integers) {
    vtkNew<vtkIntArray> array;
    array->SetName(name.c_str());
    array->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i) array->SetValue(i, values[i]);
    poly->GetPointData()->AddArray(array);
  }
  for (const auto& [name, values] : data.attributes.reals) {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name.c_str());
    array->SetNumberOfTuples(n);
    for (vtkIdType i = 0; i < n; ++i) array->SetValue(i, values[i]);
    poly->GetPointData()->AddArray(array);
  }
  if (!data.attributes.part_names.empty()) {  // what each value of `part` names, for partreg and ParaView
    vtkNew<vtkStringArray> names;
    names->SetName("part_names");
    for (const std::string& name : data.attributes.part_names) names->InsertNextValue(name);
    poly->GetFieldData()->AddArray(names);
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->SetDataModeToBinary();
  writer->WriteToOutputStringOn();  // the bytes go to any stream, a FIFO or a device included
  if (writer->Write() != 1) throw InputError("VTK could not encode the PolyData");
  out << writer->GetOutputString();
}

}  // namespace partreg::io::detail
