// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Checkpoints and restarts}
//
// A run of an hour on a shared machine may be stopped by the queue, by the
// user or by a failure of the machine. A checkpoint holds everything the
// time loop carries from one step to the next, so that a run continued
// from it (`soft-robot file.prm --restart DIR`) computes the same steps as
// the uninterrupted run, and its tip trajectory and energies are the same
// to round-off (bit for bit in the tests `cli.restart.*` of
// tests/CMakeLists.txt). What the
// time loop carries is:
// - the time and the number of steps, and the state of the HHT method at
//   the last converged step: $\mathbf u_n$, $\mathbf v_n$, $\mathbf a_n$
//   and the forces $\mathbf f_\text{int}(\mathbf u_n)$, $\mathbf
//   f_\text{ext}(t_n)$ and $\mathbf f_\text{d}(\mathbf u_n, \mathbf v_n)$,
//   which the HHT equation of the next step weights with $-\alpha$;
// - the energy account, the pressure work included, with the HHT damping,
//   traction and pressure forces of the last step that its sums go on
//   from, and the initial total energy;
// - a gas sealed in the cavity: its volume and mass at sealing, which with
//   the inflow (a function of time) and the cavity's volume give its
//   pressure (include/physics/gas_cavity.h);
// - the time-step controller (the step size, the steps since the last
//   cut-back, the cut-backs so far) and the counters of the run (steps,
//   Newton and linear iterations, factorizations);
// - the stiffness matrix $\mathbf K_{n-1}$ from which the modified Newton
//   method extrapolates the next step's matrix (SoftRobotDynamics::
//   prepare_step_tangent()), its values in the order of the matrix's
//   sparsity pattern;
// - with `Tangent update = when needed`, the matrix the next step keeps
//   (its values, its step size and the gas's rank-one term on it), which
//   the restart factorizes again;
// - the length of the trajectory file and the records of the field output
//   (the outputs so far and the time of the next one).
//
// What the linear solver keeps -- KLU's pivot sequence, ML's aggregates,
// both from the first step of the run -- is not stored: the continued run
// builds them anew for its first matrix. Where the pivots or the
// aggregates come out otherwise, the continued run agrees with the
// uninterrupted one to the tolerances of the solvers, not bit for bit.
//
// What the state $(\mathbf u_n, \mathbf v_n)$ determines is not stored but
// computed again at the restart: the stiffness $\mathbf K_n$, the damping
// matrix and the viscosity of the Kelvin-Voigt damping, which
// SoftRobotDynamics::assemble_state() records from the state a step starts
// from. The assembly is deterministic, so that they are the same bits as
// in the uninterrupted run; the restart checks this on the forces that the
// same assembly gives, which it compares with the stored ones, and reports
// the difference (zero in every test).
//
// Each MPI process writes its own part of the vectors and of the matrix
// (its locally owned rows) to a file of its own, with boost's binary
// archive, which keeps every bit of a double; a restart must therefore run
// on the same number of processes, which it checks. The checkpoint
// directory is `checkpoint/` in the output directory. It has two slots,
// `slot_0/` and `slot_1/`, each with a file `state.<rank>.bin` per
// process, and the record `latest`, which names the slot of the last
// complete checkpoint. A new checkpoint is written into the other slot,
// and `latest` is rewritten (through a temporary file and a rename, see
// output/safe_file.h) only when every process has written its file: a run
// killed while it writes a checkpoint leaves the previous one valid.
//
// The run statistics of a continued run count the steps, iterations,
// factorizations and cut-backs of the whole run, and the wall time of its
// own part.
//
// A checkpoint also records the parameters of its run (the fingerprint of
// Parameters::AllParameters, every entry but the end time and the
// checkpoint and progress intervals), the dimension, the mesh size and the
// number of processes; a restart with anything else is refused with a
// message that names what differs (an input error, exit code 1, before
// anything is written).
//
// Implemented in source/output/checkpoint.cc.

#ifndef soft_robot_output_checkpoint_h
#define soft_robot_output_checkpoint_h

#include <core/parameters.h>
#include <csignal>
#include <cstdint>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace SoftRobot
{
  using namespace dealii;

  // @sect4{What a checkpoint holds}
  //
  // The numbers are the same on every process; the vectors and the matrix
  // values are the process's own part.
  struct CheckpointData
  {
    // What the checkpoint must agree with.
    unsigned int  format_version = 3;
    unsigned int  dimension      = 0;
    unsigned int  n_processes    = 0;
    unsigned int  rank           = 0;
    std::uint64_t n_dofs         = 0;
    std::uint64_t n_cells        = 0;
    std::string   parameters;

    // The time loop.
    double       time                   = 0.;
    unsigned int steps                  = 0;
    unsigned int newton_iterations      = 0;
    unsigned int linear_iterations      = 0;
    unsigned int last_newton_iterations = 0;
    double       last_residual          = 0.;
    unsigned int factorizations         = 0;
    double       time_step              = 0.;
    unsigned int steps_since_cutback    = 0;
    unsigned int total_cutbacks         = 0;

    // The energy account (EnergyAccount, in its order).
    std::vector<double> energies;
    double              initial_total_energy = 0.;

    // The output.
    std::uint64_t                               trajectory_length = 0;
    double                                      next_output_time  = 0.;
    double                                      last_output_time  = 0.;
    std::vector<std::pair<double, std::string>> pvd_records;
    std::string                                 xdmf_records;

    // The locally owned values of the vectors, by name, and of the
    // stiffness matrix of the step before (if the run keeps it).
    std::map<std::string, std::vector<double>> vectors;
    bool                                       has_older_stiffness  = false;
    double                                     older_stiffness_time = 0.;
    std::vector<double>                        older_stiffness;

    // The gas sealed in the cavity (GasCavity::sealed_state()): its volume
    // and mass at sealing; empty without a gas.
    std::vector<double> gas_seal;

    // With `Tangent update = when needed`: the step size of the matrix the
    // next step keeps (zero if it builds its own), the matrix's values and
    // the coefficient of the gas's rank-one term on it (its vector is among
    // `vectors`).
    double              kept_matrix_dt = 0.;
    std::vector<double> kept_matrix;
    double              kept_rank_one_factor = 0.;

    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int /*version*/)
    {
      archive &format_version &dimension &n_processes &rank &n_dofs &n_cells
        &parameters;
      archive &time &steps &newton_iterations &linear_iterations
        &last_newton_iterations &last_residual &factorizations &time_step
          &steps_since_cutback &total_cutbacks;
      archive &energies        &initial_total_energy;
      archive &trajectory_length &next_output_time &last_output_time
        &pvd_records &xdmf_records;
      archive &vectors &has_older_stiffness &older_stiffness_time
                                           &older_stiffness;
      archive                              &gas_seal;
      archive &kept_matrix_dt &kept_matrix &kept_rank_one_factor;
    }
  };



  namespace Checkpoint
  {
    // The checkpoint directory of a run: `checkpoint` in its output
    // directory.
    std::string
    directory_of(const std::string &output_directory);

    // Collective: writes `data` (each process its own) as the new latest
    // checkpoint in `directory`, in the slot that the latest one does not
    // use. Throws WriteFailure on every process if a file cannot be
    // written; the previous checkpoint is then still the latest.
    void
    write(const std::string    &directory,
          const CheckpointData &data,
          const MPI_Comm        mpi_communicator);

    // Collective: the latest checkpoint in `directory` (a checkpoint
    // directory, or an output directory that holds one), this process's
    // part. Throws an input error that names the directory if there is
    // none, if it was written by another number of processes, or if it
    // cannot be read.
    CheckpointData
    read(const std::string &directory, const MPI_Comm mpi_communicator);

    // Throws an input error if `data` was not written by a run of these
    // parameters, dimension and mesh: the message names the first entry
    // that differs, with both values.
    void
    check_compatible(const CheckpointData            &data,
                     const Parameters::AllParameters &parameters,
                     const unsigned int               dimension,
                     const std::uint64_t              n_dofs,
                     const std::uint64_t              n_cells);

    // The locally owned values of a vector, and back; the latter checks
    // that the sizes agree.
    std::vector<double>
    local_values(const TrilinosWrappers::MPI::Vector &vector);
    void
    set_local_values(const std::vector<double>     &values,
                     TrilinosWrappers::MPI::Vector &vector);

    // The values of the locally owned rows of a matrix, in the order of its
    // sparsity pattern, and back into a matrix of the same pattern.
    std::vector<double>
    local_values(const TrilinosWrappers::SparseMatrix &matrix);
    void
    set_local_values(const std::vector<double>      &values,
                     TrilinosWrappers::SparseMatrix &matrix);
  } // namespace Checkpoint



  // @sect4{Interruptions}
  //
  // While an object of this class exists, SIGINT and SIGTERM set a flag
  // instead of ending the program; the time loop asks for it after every
  // step (requested()), writes a checkpoint and stops with exit code 4. A
  // second signal ends the program at once, as without the handler (the
  // handler is installed for one delivery). Under mpirun, signal mpirun:
  // it forwards SIGTERM to every process; the loop agrees on the flag with
  // a reduction, so that all processes stop after the same step even if
  // only one received the signal. (The exit code of such a run is then
  // mpirun's, 1 for Open MPI; the message is the program's.)
  class InterruptionHandler
  {
  public:
    InterruptionHandler();
    ~InterruptionHandler();

    // Collective: the signal received since the handler was installed on
    // any process (its number), or zero.
    static int
    requested(const MPI_Comm mpi_communicator);

    // The test hook: if the environment variable
    // SOFT_ROBOT_TEST_INTERRUPT_AT_STEP is `step`, process 0 sends itself
    // SIGTERM (as a user would, during the step).
    static void
    test_hook(const unsigned int step, const MPI_Comm mpi_communicator);

  private:
    struct sigaction old_interrupt;
    struct sigaction old_terminate;
  };
} // namespace SoftRobot

#endif
