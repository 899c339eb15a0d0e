// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The cost of a run}
//
// See include/output/run_statistics.h. The JSON text comes from
// nlohmann::json, with the keys in the order below.

#include <cstdio>
#include <deal.II/base/exceptions.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <output/run_statistics.h>
#include <output/safe_file.h>

namespace SoftRobot
{
  using namespace dealii;

  void
  RunStatistics::write(const std::string &file_name) const
  {
    nlohmann::ordered_json json;
    json["dimension"]                     = dimension;
    json["cells"]                         = cells;
    json["dofs"]                          = dofs;
    json["matrix_nonzeros"]               = matrix_nonzeros;
    json["multigrid_operator_complexity"] = multigrid_operator_complexity;
    json["degree"]                        = degree;
    json["mpi_processes"]                 = mpi_processes;
    json["threads_per_process"]           = threads_per_process;
    json["blas_kernels"]                  = blas_kernels;
    json["linear_solver"]                 = linear_solver;
    json["solver_in_use"]                 = solver_in_use;
    json["tangent_update"]                = tangent_update;
    json["end_time"]                      = end_time;
    json["steps"]                         = steps;
    json["newton_iterations"]             = newton_iterations;
    json["linear_iterations"]             = linear_iterations;
    json["factorizations_or_amg_setups"]  = factorizations;
    json["cutbacks"]                      = cutbacks;
    json["wall_seconds"]                  = wall_seconds;
    json["peak_memory_mb"]                = peak_memory_mb;
    json["sections"]                      = nlohmann::ordered_json::object();
    for (const auto &[name, seconds] : sections)
      json["sections"][name] = seconds;

    write_file_atomically(file_name, [&](std::ostream &out) {
      out << json.dump(2) << '\n';
    });
  }
} // namespace SoftRobot
