// SPDX-License-Identifier: MIT
// bench/vtk_encoding_bench.cpp — what base64 data inside each DataArray (VTK's "binary" mode,
// nmm's since 2026-12-01) costs against the raw appended bytes nmm wrote before (issue 43:
// ParaView 5.11 with Debian 12's expat refuses appended data), in size and in write and read
// time, measured in the same run.
//
//   bench_vtk_encoding [--repeats R] FILE.vtu|FILE.vtp...
//       each file (nmm's output, any format) is read once, then written R times (default 7)
//       with io/vtk_writer.cpp's settings (LZ4, UInt64 headers) as raw appended data and as
//       inline base64, the two alternating so that both see the same load, and each written
//       file read back by VTK's XML reader; the best time of each.
//       bench/run_benchmarks.sh runs it on the output of examples/05 and examples/09.
#include "timing.hpp"
#include <unistd.h>
#include <vtkDataObject.h>
#include <vtkDataSet.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkXMLWriter.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nmm::bench::Clock;
using nmm::bench::since;

bool is_grid(const fs::path& file) { return file.extension() == ".vtu"; }

vtkSmartPointer<vtkDataObject> read(const fs::path& file) {
  if (is_grid(file)) {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(file.c_str());
    reader->Update();
    return reader->GetOutput();
  }
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

/// io/vtk_writer.cpp's write_xml() (inline base64), or its settings before 2026-12-01 (raw
/// appended data).
template <class Writer> void write(vtkDataObject* data, const fs::path& file, bool base64) {
  vtkNew<Writer> writer;
  writer->SetInputData(data);
  writer->SetFileName(file.c_str());
  if (base64) {
    writer->SetDataModeToBinary();
  } else {
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
  }
  writer->SetCompressorTypeToLZ4();
  writer->SetHeaderTypeToUInt64();
  if (writer->Write() != 1) {
    std::fprintf(stderr, "bench_vtk_encoding: cannot write %s\n", file.c_str());
    std::exit(1);
  }
}

struct Figures {
  double bytes = 0.0;
  double write_seconds = 1e300;
  double read_seconds = 1e300;
};

void print(const std::string& name, long long cells, const Figures (&f)[2]) {
  std::printf("%-28s %9lld | %12.0f %12.0f %6.3f | %9.2f %9.2f %6.3f | %9.2f %9.2f %6.3f\n",
              name.c_str(), cells, f[0].bytes, f[1].bytes, f[1].bytes / f[0].bytes,
              1e3 * f[0].write_seconds, 1e3 * f[1].write_seconds,
              f[1].write_seconds / f[0].write_seconds, 1e3 * f[0].read_seconds,
              1e3 * f[1].read_seconds, f[1].read_seconds / f[0].read_seconds);
}

} // namespace

int main(int argc, char** argv) {
  int repeats = 7;
  std::vector<fs::path> files;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--repeats" && k + 1 < argc)
      repeats = std::max(1, std::atoi(argv[++k]));
    else
      files.emplace_back(arg);
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: bench_vtk_encoding [--repeats R] FILE.vtu|FILE.vtp...\n");
    return 2;
  }
  const fs::path work =
      fs::temp_directory_path() / ("nmm_vtk_encoding." + std::to_string(getpid()));
  fs::create_directories(work);
  std::printf("load %.1f; best of %d alternated writes and reads per file and encoding\n",
              nmm::bench::load_average(), repeats);
  std::printf("%-28s %9s | %12s %12s %6s | %9s %9s %6s | %9s %9s %6s\n", "file", "cells",
              "raw bytes", "base64 bytes", "ratio", "raw ms", "b64 ms", "ratio", "read raw",
              "read b64", "ratio");
  Figures total[2] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  long long total_cells = 0;
  for (const fs::path& file : files) {
    const vtkSmartPointer<vtkDataObject> data = read(file);
    auto* set = vtkDataSet::SafeDownCast(data);
    Figures figures[2];
    for (int r = 0; r < repeats; ++r) {
      for (int encoding = 0; encoding < 2; ++encoding) {
        const fs::path out =
            work / (std::string(encoding ? "base64" : "raw") + file.extension().string());
        const Clock::time_point start = Clock::now();
        if (is_grid(file))
          write<vtkXMLUnstructuredGridWriter>(data, out, encoding == 1);
        else
          write<vtkXMLPolyDataWriter>(data, out, encoding == 1);
        figures[encoding].write_seconds = std::min(figures[encoding].write_seconds, since(start));
        figures[encoding].bytes = static_cast<double>(fs::file_size(out));
        const Clock::time_point read_start = Clock::now();
        static_cast<void>(read(out));
        figures[encoding].read_seconds =
            std::min(figures[encoding].read_seconds, since(read_start));
      }
    }
    for (int encoding = 0; encoding < 2; ++encoding) {
      total[encoding].bytes += figures[encoding].bytes;
      total[encoding].write_seconds += figures[encoding].write_seconds;
      total[encoding].read_seconds += figures[encoding].read_seconds;
    }
    const long long cells = set != nullptr ? set->GetNumberOfCells() : 0;
    total_cells += cells;
    print(file.filename().string(), cells, figures);
  }
  if (files.size() > 1)
    print("all (sums)", total_cells, total);
  fs::remove_all(work);
  return 0;
}
