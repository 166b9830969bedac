# SPDX-License-Identifier: MIT
# Every third-party dependency comes from Debian 12 packages (scripts/deps.sh installs them).
# Each is wrapped in an imported target whose headers are SYSTEM includes, so our warning
# flags never fire inside them.

find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(Threads REQUIRED) # mesh/parallel.cpp

# CGAL: header-only on Debian 12 (5.5). Only mesh/*.cpp may use it.
find_package(CGAL REQUIRED)

# SuiteSparse CHOLMOD (Debian ships no CMake config for 5.x: find it by hand).
find_path(NMM_CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(NMM_CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(NMM_SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(nmm::cholmod INTERFACE IMPORTED)
target_include_directories(nmm::cholmod SYSTEM INTERFACE "${NMM_CHOLMOD_INCLUDE_DIR}")

# OpenBLAS, linked explicitly and ahead of CHOLMOD: its dgemm/dsyrk then win symbol
# resolution whatever the libblas.so.3 alternative points to (reference BLAS is 5.5x slower
# for the supernodal factorisation on this machine).
find_library(NMM_OPENBLAS_LIBRARY openblas REQUIRED)
find_path(NMM_OPENBLAS_INCLUDE_DIR openblas_config.h
          PATHS /usr/include/x86_64-linux-gnu /usr/include/aarch64-linux-gnu
          PATH_SUFFIXES openblas-pthread openblas REQUIRED)
target_link_libraries(nmm::cholmod INTERFACE "${NMM_OPENBLAS_LIBRARY}" "${NMM_CHOLMOD_LIBRARY}"
                                             "${NMM_SUITESPARSECONFIG_LIBRARY}")
add_library(nmm::openblas INTERFACE IMPORTED)
target_include_directories(nmm::openblas SYSTEM INTERFACE "${NMM_OPENBLAS_INCLUDE_DIR}")
target_link_libraries(nmm::openblas INTERFACE "${NMM_OPENBLAS_LIBRARY}")

# gmsh C++ API (libgmsh-dev ships no CMake config).
find_path(NMM_GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(NMM_GMSH_LIBRARY gmsh REQUIRED)
add_library(nmm::gmsh INTERFACE IMPORTED)
target_include_directories(nmm::gmsh SYSTEM INTERFACE "${NMM_GMSH_INCLUDE_DIR}")
target_link_libraries(nmm::gmsh INTERFACE "${NMM_GMSH_LIBRARY}")

# IOXMLParser and FiltersGeneral: the tests read .pvd files with VTK's XML parser and
# triangulate written polygons as ParaView's Tetrahedralize filter does.
find_package(VTK 9.1 REQUIRED COMPONENTS CommonCore CommonDataModel IOXML IOXMLParser
                                         FiltersGeneral)
find_package(tomlplusplus 3 REQUIRED)
find_package(CLI11 2 REQUIRED)

if(NMM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(NMM_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
