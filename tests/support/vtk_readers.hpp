// SPDX-License-Identifier: MIT
// tests/support/vtk_readers.hpp — read nmm's VTK output back with VTK's own readers.
#pragma once

#include <gtest/gtest.h>
#include <vtkAbstractArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>

#include <filesystem>
#include <string>
#include <vector>

namespace nmm::testing {

inline vtkSmartPointer<vtkUnstructuredGrid> read_vtu(const std::filesystem::path& file) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  EXPECT_TRUE(reader->CanReadFile(file.c_str())) << file;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

inline vtkSmartPointer<vtkPolyData> read_vtp(const std::filesystem::path& file) {
  vtkNew<vtkXMLPolyDataReader> reader;
  EXPECT_TRUE(reader->CanReadFile(file.c_str())) << file;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

/// The component names of a read-back array ("" for a component without one).
inline std::vector<std::string> component_names(vtkFieldData* data, const std::string& name) {
  std::vector<std::string> names;
  vtkAbstractArray* array = data->GetAbstractArray(name.c_str());
  EXPECT_NE(array, nullptr) << "no array " << name;
  if (array == nullptr)
    return names;
  for (int c = 0; c < array->GetNumberOfComponents(); ++c) {
    const char* component = array->GetComponentName(c);
    names.emplace_back(component == nullptr ? "" : component);
  }
  return names;
}

/// The values of a read-back text array.
inline std::vector<std::string> text_values(vtkFieldData* data, const std::string& name) {
  std::vector<std::string> values;
  auto* array = vtkStringArray::SafeDownCast(data->GetAbstractArray(name.c_str()));
  EXPECT_NE(array, nullptr) << "no text array " << name;
  if (array == nullptr)
    return values;
  for (vtkIdType k = 0; k < array->GetNumberOfValues(); ++k)
    values.push_back(array->GetValue(k));
  return values;
}

/// One DataSet line of a .pvd.
struct PvdEntry {
  double time = 0.0; ///< the timestep attribute, read with std::stod
  int part = 0;
  std::string name; ///< the part's name ("elements", "contacts"...), empty when it has none
  std::string file; ///< as written: relative to the .pvd's folder
};

/// The DataSet entries of a .pvd, parsed by VTK's XML parser; fails the test when it is not
/// a well-formed VTK Collection.
inline std::vector<PvdEntry> read_pvd(const std::filesystem::path& pvd) {
  std::vector<PvdEntry> entries;
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromFile(pvd.c_str()));
  EXPECT_NE(root, nullptr) << pvd << " does not parse";
  if (root == nullptr)
    return entries;
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  EXPECT_NE(collection, nullptr);
  if (collection == nullptr)
    return entries;
  for (int k = 0; k < collection->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* dataset = collection->GetNestedElement(k);
    EXPECT_STREQ(dataset->GetName(), "DataSet");
    const auto attribute = [&](const char* name) {
      const char* value = dataset->GetAttribute(name);
      return std::string(value == nullptr ? "" : value);
    };
    const std::string part = attribute("part");
    entries.push_back({std::stod(attribute("timestep")), part.empty() ? 0 : std::stoi(part),
                       attribute("name"), attribute("file")});
  }
  return entries;
}

} // namespace nmm::testing
