// SPDX-License-Identifier: MIT
// tests/support/vtk_readers.hpp — read nmm's VTK output back with VTK's own readers.
#pragma once

#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
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

/// One DataSet line of a .pvd.
struct PvdEntry {
  double time = 0.0; ///< the timestep attribute, read with std::stod
  int part = 0;
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
    entries.push_back(
        {std::stod(attribute("timestep")), part.empty() ? 0 : std::stoi(part), attribute("file")});
  }
  return entries;
}

} // namespace nmm::testing
