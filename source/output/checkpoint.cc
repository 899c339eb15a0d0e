// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Checkpoints and restarts}
//
// See include/output/checkpoint.h.

#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/map.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>
#include <cerrno>
#include <core/exceptions.h>
#include <cstdlib>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <filesystem>
#include <fstream>
#include <output/checkpoint.h>
#include <output/safe_file.h>
#include <sstream>

namespace SoftRobot
{
  namespace Checkpoint
  {
    namespace
    {
      std::string
      state_file(const std::string &slot, const unsigned int rank)
      {
        return slot + "/state." + Utilities::int_to_string(rank) + ".bin";
      }

      // The first word of the record `latest`: the slot it names.
      std::string
      latest_slot(const std::string &directory)
      {
        std::ifstream record(directory + "/latest");
        std::string   slot;
        record >> slot;
        return slot;
      }
    } // namespace



    std::string
    directory_of(const std::string &output_directory)
    {
      return output_directory + "/checkpoint";
    }



    // @sect4{Checkpoint::write}
    //
    // Process 0 empties the slot that the latest checkpoint does not use;
    // every process writes its file there; when all have, process 0
    // rewrites `latest` to name the slot. A failure anywhere is known to
    // every process before `latest` is touched.
    void
    write(const std::string    &directory,
          const CheckpointData &data,
          const MPI_Comm        mpi_communicator)
    {
      const bool root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
      std::string failure;
      std::string slot;
      if (root)
        {
          slot = (latest_slot(directory) == "slot_0") ? "slot_1" : "slot_0";
          std::error_code error;
          std::filesystem::remove_all(directory + "/" + slot, error);
          std::filesystem::create_directories(directory + "/" + slot, error);
          if (error)
            failure = "Cannot create the checkpoint directory '" + directory +
                      "/" + slot + "': " + error.message() + ".";
        }
      fail_everywhere(failure, mpi_communicator);
      slot = Utilities::MPI::broadcast(mpi_communicator, slot, 0);

      const std::string name = state_file(directory + "/" + slot, data.rank);
      try
        {
          errno = 0;
          std::ofstream file(name, std::ios::binary | std::ios::trunc);
          check_written(file, name);
          {
            boost::archive::binary_oarchive archive(file);
            archive << data;
          }
          file.close();
          check_written(file, name);
        }
      catch (WriteFailure &error)
        {
          failure = error.what();
        }
      fail_everywhere(failure, mpi_communicator);

      if (root)
        try
          {
            write_file_atomically(directory + "/latest",
                                  [&](std::ostream &out) {
                                    out << slot << "\nstep " << data.steps
                                        << "\ntime " << data.time
                                        << "\nprocesses " << data.n_processes
                                        << '\n';
                                  });
          }
        catch (WriteFailure &error)
          {
            failure = error.what();
          }
      fail_everywhere(failure, mpi_communicator);
    }



    // @sect4{Checkpoint::read}
    CheckpointData
    read(const std::string &directory_name, const MPI_Comm mpi_communicator)
    {
      std::string directory = directory_name;
      if (!std::filesystem::exists(directory + "/latest") &&
          std::filesystem::exists(directory_of(directory) + "/latest"))
        directory = directory_of(directory);
      const std::string where =
        "Cannot restart from '" + directory_name + "': ";
      AssertThrow(std::filesystem::exists(directory + "/latest"),
                  ExcMessage(where +
                             "it holds no checkpoint (no file 'latest' there "
                             "or in its directory 'checkpoint'); a run "
                             "writes one every Output/Checkpoint interval "
                             "steps and when it is interrupted."));

      const unsigned int n_processes =
        Utilities::MPI::n_mpi_processes(mpi_communicator);
      const unsigned int rank =
        Utilities::MPI::this_mpi_process(mpi_communicator);
      std::ifstream record(directory + "/latest");
      std::string   slot, word;
      unsigned int  written_by = 0;
      record >> slot;
      while (record >> word)
        if (word == "processes")
          record >> written_by;
      AssertThrow(written_by == n_processes,
                  ExcMessage(where + "the checkpoint was written by " +
                             std::to_string(written_by) +
                             " MPI processes, and this run has " +
                             std::to_string(n_processes) +
                             "; restart it on as many processes."));

      const std::string name = state_file(directory + "/" + slot, rank);
      CheckpointData    data;
      std::string       problem;
      try
        {
          std::ifstream file(name, std::ios::binary);
          if (!file)
            problem = "cannot open '" + name + "'.";
          else
            {
              boost::archive::binary_iarchive archive(file);
              archive >> data;
            }
        }
      catch (std::exception &error)
        {
          problem = "'" + name + "' cannot be read (" + error.what() + ").";
        }
      if (problem.empty() &&
          data.format_version != CheckpointData().format_version)
        problem = "'" + name +
                  "' is of another version of the checkpoint "
                  "format (" +
                  std::to_string(data.format_version) + ").";
      if (problem.empty() &&
          (data.rank != rank || data.n_processes != n_processes))
        problem = "'" + name + "' is not the part of process " +
                  std::to_string(rank) + ".";
      // The first problem on any process, known to all.
      const std::vector<std::string> problems =
        Utilities::MPI::all_gather(mpi_communicator, problem);
      for (const std::string &p : problems)
        AssertThrow(p.empty(), ExcMessage(where + p));
      return data;
    }



    // @sect4{Checkpoint::check_compatible}
    //
    // The fingerprints are compared entry by entry, so that the message
    // names the entry that differs.
    void
    check_compatible(const CheckpointData            &data,
                     const Parameters::AllParameters &parameters,
                     const unsigned int               dimension,
                     const std::uint64_t              n_dofs,
                     const std::uint64_t              n_cells)
    {
      const std::string where = parameters.where() + "cannot restart from '" +
                                parameters.restart_directory + "': ";
      const auto entries = [](const std::string &fingerprint) {
        std::map<std::string, std::string> result;
        std::istringstream                 lines(fingerprint);
        std::string                        line;
        while (std::getline(lines, line))
          {
            const auto equals = line.find(" = ");
            result[line.substr(0, equals)] =
              (equals == std::string::npos) ? "" : line.substr(equals + 3);
          }
        return result;
      };
      const auto stored = entries(data.parameters);
      const auto now    = entries(parameters.fingerprint);
      for (const auto &[entry, value] : now)
        {
          const auto        old = stored.find(entry);
          const std::string old_value =
            (old == stored.end()) ? "(not an entry)" : old->second;
          AssertThrow(old_value == value,
                      ExcMessage(where + "the checkpoint's run had " + entry +
                                 " = " + old_value + ", this run has " + value +
                                 ". Only Time integration/End time, "
                                 "Output/Checkpoint interval and "
                                 "Output/Progress interval may change."));
        }
      AssertThrow(stored.size() == now.size(),
                  ExcMessage(where + "the checkpoint's parameters have entries "
                                     "this program does not know."));
      AssertThrow(data.dimension == dimension && data.n_dofs == n_dofs &&
                    data.n_cells == n_cells,
                  ExcMessage(where + "the checkpoint is of a " +
                             std::to_string(data.dimension) + "D mesh of " +
                             std::to_string(data.n_cells) + " cells and " +
                             std::to_string(data.n_dofs) +
                             " degrees of freedom, this run's is " +
                             std::to_string(dimension) + "D with " +
                             std::to_string(n_cells) + " cells and " +
                             std::to_string(n_dofs) +
                             " (has the mesh file changed?)."));
    }



    // @sect4{The values of vectors and matrices}
    std::vector<double>
    local_values(const TrilinosWrappers::MPI::Vector &vector)
    {
      return std::vector<double>(vector.begin(), vector.end());
    }



    void
    set_local_values(const std::vector<double>     &values,
                     TrilinosWrappers::MPI::Vector &vector)
    {
      AssertThrow(values.size() == vector.locally_owned_size(),
                  ExcMessage("The checkpoint has a vector of " +
                             std::to_string(values.size()) +
                             " values where this process owns " +
                             std::to_string(vector.locally_owned_size()) +
                             "."));
      std::copy(values.begin(), values.end(), vector.begin());
    }



    std::vector<double>
    local_values(const TrilinosWrappers::SparseMatrix &matrix)
    {
      const Epetra_CrsMatrix &epetra = matrix.trilinos_matrix();
      std::vector<double>     values;
      values.reserve(epetra.NumMyNonzeros());
      for (int row = 0; row < epetra.NumMyRows(); ++row)
        {
          int     n_entries = 0;
          double *row_values;
          int    *columns;
          epetra.ExtractMyRowView(row, n_entries, row_values, columns);
          values.insert(values.end(), row_values, row_values + n_entries);
        }
      return values;
    }



    void
    set_local_values(const std::vector<double>      &values,
                     TrilinosWrappers::SparseMatrix &matrix)
    {
      // deal.II gives the Epetra matrix as const only; the values are
      // written in place, in the pattern the matrix already has.
      Epetra_CrsMatrix &epetra =
        const_cast<Epetra_CrsMatrix &>(matrix.trilinos_matrix());
      AssertThrow(values.size() ==
                    static_cast<std::size_t>(epetra.NumMyNonzeros()),
                  ExcMessage("The checkpoint has a matrix of " +
                             std::to_string(values.size()) +
                             " values where this process has " +
                             std::to_string(epetra.NumMyNonzeros()) + "."));
      std::size_t next = 0;
      for (int row = 0; row < epetra.NumMyRows(); ++row)
        {
          int     n_entries = 0;
          double *row_values;
          int    *columns;
          epetra.ExtractMyRowView(row, n_entries, row_values, columns);
          for (int i = 0; i < n_entries; ++i)
            row_values[i] = values[next++];
        }
    }
  } // namespace Checkpoint



  // @sect4{InterruptionHandler}
  //
  // The handler only stores the signal's number in a variable of type
  // `volatile sig_atomic_t`, the one thing a signal handler may safely do;
  // SA_RESETHAND restores the default action for the next signal.
  namespace
  {
    volatile std::sig_atomic_t received_signal = 0;

    extern "C" void
    record_signal(const int signal_number)
    {
      received_signal = signal_number;
    }
  } // namespace



  InterruptionHandler::InterruptionHandler()
  {
    received_signal         = 0;
    struct sigaction action = {};
    action.sa_handler       = record_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &old_interrupt);
    sigaction(SIGTERM, &action, &old_terminate);
  }



  InterruptionHandler::~InterruptionHandler()
  {
    sigaction(SIGINT, &old_interrupt, nullptr);
    sigaction(SIGTERM, &old_terminate, nullptr);
  }



  int
  InterruptionHandler::requested(const MPI_Comm mpi_communicator)
  {
    return Utilities::MPI::max(static_cast<int>(received_signal),
                               mpi_communicator);
  }



  void
  InterruptionHandler::test_hook(const unsigned int step,
                                 const MPI_Comm     mpi_communicator)
  {
    const char *value = std::getenv("SOFT_ROBOT_TEST_INTERRUPT_AT_STEP");
    if (value != nullptr &&
        Utilities::MPI::this_mpi_process(mpi_communicator) == 0 &&
        std::to_string(step) == value)
      std::raise(SIGTERM);
  }
} // namespace SoftRobot
