// SPDX-License-Identifier: MIT
// Sparse assembly on a regular 2D mesh (n x n nodes, two triangles per square, d dofs per
// node, so 3d x 3d local matrices: d = 2 is P1 elasticity / order-0 covers, d = 6 order-1
// covers, d = 12 order-2 covers), timed in one process:
//   (a) pattern build (SparsityBuilder: add every element, build)
//   (b) plan build (Assembler::plan for every element)
//   (c) assembly by plan, per step (zero + add(plan, local) for every element)
//   (d) assembly by search (zero + add(dofs, local))
//   (e) Eigen triplets (upper triangle) + setFromTriplets
//   (f) CHOLMOD numeric factorisation + solve (symbolic analysis timed apart)
// Every time is the best of several repeats (see best_seconds). Run by hand, not by ctest.
// Usage: bench_assembly [--dofs 1e4,1e5,1e6] [--local 6,18,36] [--no-factor]
#include "solver/assembler.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/sparsity.hpp"
#include "solver/threads.hpp"

#include "timing.hpp"
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

using nmm::bench::best_seconds;

struct Mesh {
  int n_dofs = 0;
  int n_local = 0;               // 3 * dofs per node
  std::vector<int> element_dofs; // n_local per element, node by node
  [[nodiscard]] std::size_t n_elements() const {
    return element_dofs.size() / static_cast<std::size_t>(n_local);
  }
  [[nodiscard]] std::span<const int> dofs(std::size_t element) const {
    return std::span<const int>(element_dofs)
        .subspan(element * static_cast<std::size_t>(n_local), static_cast<std::size_t>(n_local));
  }
};

// n x n nodes, d dofs per node, every grid square cut into two triangles.
Mesh make_grid_mesh(int n, int d) {
  Mesh mesh;
  mesh.n_dofs = n * n * d;
  mesh.n_local = 3 * d;
  mesh.element_dofs.reserve(static_cast<std::size_t>(2 * (n - 1) * (n - 1) * 3 * d));
  auto push_node = [&](int i, int j) {
    for (int c = 0; c < d; ++c)
      mesh.element_dofs.push_back((i * n + j) * d + c);
  };
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      push_node(i, j);
      push_node(i, j + 1);
      push_node(i + 1, j);
      push_node(i + 1, j + 1);
      push_node(i + 1, j);
      push_node(i, j + 1);
    }
  }
  return mesh;
}

// Two SPD local matrices (the two triangle orientations of the grid). For d = 2 the P1
// plane-strain stiffness of a unit right triangle plus a mass-like diagonal (Shi's 2M/dt^2);
// otherwise G^T G / k + I for a random G, which has the same effect on the scatter.
std::vector<Eigen::MatrixXd> make_local_matrices(int n_local) {
  std::vector<Eigen::MatrixXd> locals;
  if (n_local == 6) {
    const double e = 1.0;
    const double nu = 0.25;
    Eigen::Matrix3d elasticity;
    const double f = e / ((1 + nu) * (1 - 2 * nu));
    elasticity << f * (1 - nu), f * nu, 0, f * nu, f * (1 - nu), 0, 0, 0, f * (1 - 2 * nu) / 2;
    const std::vector<Eigen::Matrix<double, 3, 2>> corners{
        (Eigen::Matrix<double, 3, 2>() << 0, 0, 1, 0, 0, 1).finished(),
        (Eigen::Matrix<double, 3, 2>() << 1, 1, 0, 1, 1, 0).finished()};
    for (const auto& x : corners) {
      const double two_area =
          (x(1, 0) - x(0, 0)) * (x(2, 1) - x(0, 1)) - (x(2, 0) - x(0, 0)) * (x(1, 1) - x(0, 1));
      Eigen::Matrix<double, 3, 6> strain = Eigen::Matrix<double, 3, 6>::Zero();
      for (int a = 0; a < 3; ++a) {
        const int b = (a + 1) % 3;
        const int c = (a + 2) % 3;
        const double dx = (x(b, 1) - x(c, 1)) / two_area; // d(phi_a)/dx
        const double dy = (x(c, 0) - x(b, 0)) / two_area; // d(phi_a)/dy
        strain(0, 2 * a) = dx;
        strain(1, 2 * a + 1) = dy;
        strain(2, 2 * a) = dy;
        strain(2, 2 * a + 1) = dx;
      }
      Eigen::MatrixXd local = std::abs(two_area) / 2 * strain.transpose() * elasticity * strain;
      local.diagonal().array() += 0.05;
      locals.push_back(local);
    }
    return locals;
  }
  std::mt19937 random(42);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int orientation = 0; orientation < 2; ++orientation) {
    Eigen::MatrixXd g(n_local, n_local);
    for (Eigen::Index k = 0; k < g.size(); ++k)
      g.data()[k] = value(random);
    Eigen::MatrixXd local = g.transpose() * g / n_local;
    local.diagonal().array() += 1.0;
    locals.push_back(local);
  }
  return locals;
}

struct Row {
  double seconds = 0.0;
  const char* name = "";
};

void run_case(int target_dofs, int n_local, bool factor) {
  const int d = n_local / 3;
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(target_dofs) / d)));
  const Mesh mesh = make_grid_mesh(n, d);
  const std::vector<Eigen::MatrixXd> locals = make_local_matrices(n_local);
  const std::size_t n_elements = mesh.n_elements();
  // Fewer repeats for the big cases; best-of keeps noise from the shared machine out.
  const int repeats = mesh.n_dofs <= 200000 ? 7 : 3;

  nmm::SparsityBuilder builder(mesh.n_dofs);
  nmm::SparsityPattern pattern;
  const double pattern_seconds = best_seconds(repeats, [&] {
    builder.clear();
    for (std::size_t e = 0; e < n_elements; ++e)
      builder.add(mesh.dofs(e));
    pattern = builder.build();
  });

  nmm::Assembler assembler(pattern);
  std::vector<int> plans(n_elements);
  const double plan_seconds = best_seconds(repeats, [&] {
    assembler.clear_plans();
    for (std::size_t e = 0; e < n_elements; ++e)
      plans[e] = assembler.plan(mesh.dofs(e));
  });

  const double plan_assembly_seconds = best_seconds(repeats, [&] {
    assembler.zero();
    for (std::size_t e = 0; e < n_elements; ++e)
      assembler.add(plans[e], locals[e % 2]);
  });
  const nmm::SparseMatrix by_plan = assembler.matrix();

  const double search_assembly_seconds = best_seconds(repeats, [&] {
    assembler.zero();
    for (std::size_t e = 0; e < n_elements; ++e)
      assembler.add(mesh.dofs(e), locals[e % 2]);
  });

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(n_elements * static_cast<std::size_t>(n_local * (n_local + 1) / 2));
  nmm::SparseMatrix by_triplets;
  const double triplet_seconds = best_seconds(repeats, [&] {
    triplets.clear();
    for (std::size_t e = 0; e < n_elements; ++e) {
      const std::span<const int> dofs = mesh.dofs(e);
      const Eigen::MatrixXd& local = locals[e % 2];
      for (int b = 0; b < n_local; ++b) {
        for (int a = 0; a < n_local; ++a) {
          const int row = dofs[static_cast<std::size_t>(a)];
          const int column = dofs[static_cast<std::size_t>(b)];
          if (row <= column)
            triplets.emplace_back(row, column, local(a, b));
        }
      }
    }
    nmm::SparseMatrix matrix(mesh.n_dofs, mesh.n_dofs);
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    by_triplets = std::move(matrix);
  });
  triplets = {};

  // The three assemblies must agree before their times mean anything.
  const double scale = Eigen::Map<const Eigen::VectorXd>(by_plan.valuePtr(), by_plan.nonZeros())
                           .lpNorm<Eigen::Infinity>();
  const double plan_vs_search =
      (Eigen::VectorXd::Map(by_plan.valuePtr(), by_plan.nonZeros()) -
       Eigen::VectorXd::Map(assembler.matrix().valuePtr(), assembler.matrix().nonZeros()))
          .lpNorm<Eigen::Infinity>() /
      scale;
  const double plan_vs_triplets = (by_plan - by_triplets).norm() / by_triplets.norm();
  if (by_triplets.nonZeros() != by_plan.nonZeros() || plan_vs_search > 1e-14 ||
      plan_vs_triplets > 1e-14) {
    std::fprintf(stderr, "assemblies disagree: nnz %ld vs %ld, %.3g, %.3g\n",
                 static_cast<long>(by_triplets.nonZeros()), static_cast<long>(by_plan.nonZeros()),
                 plan_vs_search, plan_vs_triplets);
    std::exit(1);
  }

  double analyze_seconds = 0.0;
  double factor_seconds = 0.0;
  if (factor) {
    nmm::CholmodSolver solver;
    analyze_seconds = best_seconds(1, [&] {
      if (solver.analyze(by_plan) != nmm::SolveStatus::ok)
        std::abort();
    });
    const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(mesh.n_dofs);
    Eigen::VectorXd x;
    factor_seconds = best_seconds(mesh.n_dofs <= 200000 ? 3 : 1, [&] {
      if (solver.factorize(by_plan) != nmm::SolveStatus::ok ||
          solver.solve(rhs, x) != nmm::SolveStatus::ok)
        std::abort();
    });
  }

  std::printf("\n%d dofs (%dx%d nodes, %d dofs/node), %zu elements of %dx%d, %d stored "
              "nonzeros (%.1f per dof), %zu local entries scattered\n",
              mesh.n_dofs, n, n, d, n_elements, n_local, n_local, pattern.n_nonzeros(),
              static_cast<double>(pattern.n_nonzeros()) / mesh.n_dofs,
              n_elements * static_cast<std::size_t>(n_local * (n_local + 1) / 2));
  const Row rows[] = {{pattern_seconds, "(a) pattern build"},
                      {plan_seconds, "(b) plan build"},
                      {plan_assembly_seconds, "(c) assembly by plan"},
                      {search_assembly_seconds, "(d) assembly by search"},
                      {triplet_seconds, "(e) triplets + setFromTriplets"},
                      {factor_seconds, "(f) CHOLMOD factor + solve"}};
  std::printf("| step | time | per dof | vs (e) | vs (f) |\n| --- | --- | --- | --- | --- |\n");
  for (const Row& row : rows) {
    if (!factor && &row == &rows[5])
      continue;
    std::printf("| %s | %.4g s | %.3f us | %.3f |", row.name, row.seconds,
                row.seconds / mesh.n_dofs * 1e6, row.seconds / triplet_seconds);
    if (factor)
      std::printf(" %.4f |\n", row.seconds / factor_seconds);
    else
      std::printf(" - |\n");
  }
  if (factor)
    std::printf("| CHOLMOD symbolic analysis (once per pattern) | %.4g s | %.3f us | %.3f | "
                "%.4f |\n",
                analyze_seconds, analyze_seconds / mesh.n_dofs * 1e6,
                analyze_seconds / triplet_seconds, analyze_seconds / factor_seconds);
  std::printf("triplets / plan assembly: %.2fx; search / plan: %.2fx; (pattern + plans + "
              "assembly) / triplets: %.2f\n",
              triplet_seconds / plan_assembly_seconds,
              search_assembly_seconds / plan_assembly_seconds,
              (pattern_seconds + plan_seconds + plan_assembly_seconds) / triplet_seconds);
  std::fflush(stdout);
}

std::vector<int> parse_list(const char* text) {
  std::vector<int> values;
  std::string item;
  for (const char* c = text;; ++c) {
    if (*c == ',' || *c == '\0') {
      if (!item.empty())
        values.push_back(static_cast<int>(std::strtod(item.c_str(), nullptr)));
      item.clear();
      if (*c == '\0')
        break;
    } else {
      item += *c;
    }
  }
  return values;
}

} // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes{10000, 100000, 1000000};
  std::vector<int> local_sizes{6, 18, 36};
  bool factor = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--dofs" && i + 1 < argc) {
      sizes = parse_list(argv[++i]);
    } else if (arg == "--local" && i + 1 < argc) {
      local_sizes = parse_list(argv[++i]);
    } else if (arg == "--no-factor") {
      factor = false;
    } else {
      std::fprintf(stderr, "usage: %s [--dofs 1e4,1e5,1e6] [--local 6,18,36] [--no-factor]\n",
                   argv[0]);
      return 2;
    }
  }
  nmm::limit_threads(nmm::available_cores());
  std::printf("%s; %s; usable cores %d\n", nmm::cholmod_version().c_str(),
              nmm::blas_description().c_str(), nmm::available_cores());
  for (const int n_local : local_sizes) {
    if (n_local % 3 != 0) {
      std::fprintf(stderr, "local size must be 3 x dofs per node\n");
      return 2;
    }
    for (const int target : sizes)
      run_case(target, n_local, factor);
  }
  return 0;
}
