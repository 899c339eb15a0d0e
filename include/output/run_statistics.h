// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The cost of a run}
//
// What a run cost, in a small machine-readable file, `run_statistics.json`
// in the output directory, for benchmarks and scripts: mesh size, counts of
// the solver's work, the wall time of each timed section (the largest over
// the processes), and the peak resident memory, summed over the processes.
//
// Implemented in source/output/run_statistics.cc.

#ifndef soft_robot_output_run_statistics_h
#define soft_robot_output_run_statistics_h

#include <cstdint>
#include <map>
#include <string>

namespace SoftRobot
{
  struct RunStatistics
  {
    unsigned int  dimension                     = 0;
    std::uint64_t cells                         = 0;
    std::uint64_t dofs                          = 0;
    std::uint64_t matrix_nonzeros               = 0;
    double        multigrid_operator_complexity = 0.;
    unsigned int  degree                        = 0;
    unsigned int  mpi_processes                 = 0;
    unsigned int  threads_per_process           = 0;
    // OpenBLAS's name for the kernels in use ("SkylakeX", "Haswell", ...;
    // solvers/blas_kernels.h), "" with another BLAS.
    std::string blas_kernels;
    std::string linear_solver;
    // The solver prepared last ("Amesos_Klu", "Amesos_Mumps", "CG with
    // ML", ...): what `Direct solver = automatic` chose.
    std::string  solver_in_use;
    std::string  tangent_update;
    double       end_time          = 0.;
    unsigned int steps             = 0;
    unsigned int newton_iterations = 0;
    unsigned int linear_iterations = 0;
    // Matrix factorizations or multigrid set-ups.
    unsigned int factorizations = 0;
    unsigned int cutbacks       = 0;
    double       wall_seconds   = 0.;
    double       peak_memory_mb = 0.;
    // Wall seconds per timed section.
    std::map<std::string, double> sections;

    // Writes the JSON file (through a temporary file that is renamed, so
    // that a reader never sees half of it).
    void
    write(const std::string &file_name) const;
  };
} // namespace SoftRobot

#endif
