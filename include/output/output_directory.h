// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The output directory}
//
// A run writes into its `Problem/Output directory` only after all of its
// input has been checked and its initial state computed (see
// SoftRobotDynamics::run()); a run that fails its input leaves the
// directory byte for byte as it was. When it starts writing, the directory
// may hold the output of an earlier run. Mixing the two -- a new PVD record
// beside the old run's VTU files, an old `run_statistics.json` beside a new
// trajectory that was stopped -- gives a result that looks whole and is
// not; overwriting it silently destroys a result that may have taken an
// hour. So by default (`Output/Existing output = refuse`) a run stops with
// a message that names the directory and the files; with `replace` it
// removes the earlier run's files of the kinds this program writes (and
// nothing else) before it writes its own.
//
// The files of a run are: the trajectory (`Output/Trajectory file`), the
// field output (`solution.pvd`, `solution.xdmf`, `solution_*`), the run
// statistics, the spectra and the directory `checkpoint`. A restart, which
// continues a run in its own directory, appends to the trajectory and goes
// on with the records instead (the writers keep their records in memory
// and rewrite them whole, see FieldOutput), and is the one case where
// these files are expected; it does not call prepare_output_directory().
//
// Implemented in source/output/output_directory.cc.

#ifndef soft_robot_output_output_directory_h
#define soft_robot_output_output_directory_h

#include <core/parameters.h>
#include <deal.II/base/mpi.h>
#include <string>
#include <vector>

namespace SoftRobot
{
  // Whether `file_name` (without a directory) is one of the names the field
  // output, the run statistics or the spectra use.
  bool
  is_reserved_output_name(const std::string &file_name);

  // The files of an earlier run in `directory` (names without the
  // directory, sorted); empty if the directory does not exist.
  std::vector<std::string>
  earlier_output_files(const std::string &directory,
                       const std::string &trajectory_file);

  // Collective. Throws an input error if the directory holds an earlier
  // run's files and the parameters say 'refuse'; otherwise creates the
  // directory (WriteFailure if it cannot) and, with 'replace', removes
  // those files.
  void
  prepare_output_directory(const Parameters::AllParameters &parameters,
                           const MPI_Comm                   mpi_communicator);
} // namespace SoftRobot

#endif
