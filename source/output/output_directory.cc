// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The output directory}
//
// See include/output/output_directory.h.

#include <algorithm>
#include <core/exceptions.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <filesystem>
#include <output/output_directory.h>
#include <output/safe_file.h>
#include <system_error>

namespace SoftRobot
{
  using namespace dealii;

  bool
  is_reserved_output_name(const std::string &file_name)
  {
    for (const char *name : {"solution.pvd",
                             "solution.xdmf",
                             "run_statistics.json",
                             "tip_spectrum.csv",
                             "tip_spectrum_magnitudes.csv"})
      if (file_name == name)
        return true;
    return file_name.rfind("solution_", 0) == 0;
  }



  std::vector<std::string>
  earlier_output_files(const std::string &directory,
                       const std::string &trajectory_file)
  {
    std::vector<std::string> files;
    std::error_code          error;
    if (!std::filesystem::is_directory(directory, error))
      return files;
    for (const auto &entry :
         std::filesystem::directory_iterator(directory, error))
      {
        // Files (and links), and of the directories only the checkpoints
        // (output/checkpoint.h): a stale checkpoint beside a new run's
        // output would continue the old run into the new one's files.
        const std::string name = entry.path().filename().string();
        if (entry.is_directory(error))
          {
            if (name == "checkpoint")
              files.push_back(name);
            continue;
          }
        const bool temporary =
          name.size() > 4 && name.substr(name.size() - 4) == ".tmp";
        if (!temporary &&
            (name == trajectory_file || is_reserved_output_name(name)))
          files.push_back(name);
      }
    std::sort(files.begin(), files.end());
    return files;
  }



  // @sect4{prepare_output_directory}
  //
  // Process 0 looks at the directory and acts; the others learn the outcome
  // from it, so that all of them throw the same error or none.
  void
  prepare_output_directory(const Parameters::AllParameters &parameters,
                           const MPI_Comm                   mpi_communicator)
  {
    const std::string &directory = parameters.output_directory;
    std::string        refusal, failure;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        const std::vector<std::string> files =
          earlier_output_files(directory, parameters.trajectory_file);
        if (!files.empty() && parameters.existing_output ==
                                Parameters::Output::ExistingOutput::refuse)
          {
            std::string listed;
            for (unsigned int i = 0; i < std::min<std::size_t>(files.size(), 3);
                 ++i)
              listed += (i == 0 ? "" : ", ") + files[i];
            if (files.size() > 3)
              listed += " and " + std::to_string(files.size() - 3) + " more";
            refusal = parameters.where() + "Problem/Output directory '" +
                      directory + "' holds the output of an earlier run (" +
                      listed +
                      "). Nothing was written. Choose another directory, "
                      "move those files away, or set 'Output/Existing "
                      "output = replace' to replace them.";
          }
        else
          {
            std::error_code error;
            std::filesystem::create_directories(directory, error);
            if (error || !std::filesystem::is_directory(directory))
              failure =
                "Cannot create the output directory '" + directory +
                "': " + (error ? error.message() : "it is not a directory") +
                ".";
            for (const std::string &name : files)
              if (failure.empty() && name != parameters.trajectory_file)
                {
                  std::filesystem::remove_all(std::filesystem::path(directory) /
                                                name,
                                              error);
                  if (error)
                    failure = "Cannot remove '" + directory + "/" + name +
                              "' of the earlier run: " + error.message() + ".";
                }
          }
      }
    refusal = Utilities::MPI::broadcast(mpi_communicator, refusal, 0);
    AssertThrow(refusal.empty(), ExcMessage(refusal));
    fail_everywhere(failure, mpi_communicator);
  }
} // namespace SoftRobot
