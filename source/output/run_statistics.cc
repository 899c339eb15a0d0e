// @sect3{The cost of a run}
//
// See include/output/run_statistics.h. The JSON text comes from
// nlohmann::json, with the keys in the order below.

#include <deal.II/base/exceptions.h>
#include <nlohmann/json.hpp>
#include <output/run_statistics.h>

#include <cstdio>
#include <fstream>

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
    json["linear_solver"]                 = linear_solver;
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

    const std::string temporary = file_name + ".tmp";
    {
      std::ofstream file(temporary);
      file << json.dump(2) << '\n';
      file.close();
      AssertThrow(file,
                  ExcMessage("Cannot write the run statistics '" + temporary +
                             "'."));
    }
    AssertThrow(std::rename(temporary.c_str(), file_name.c_str()) == 0,
                ExcMessage("Cannot rename '" + temporary + "' to '" +
                           file_name + "'."));
  }
} // namespace SoftRobot
