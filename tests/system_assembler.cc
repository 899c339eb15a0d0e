// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The fast global addition builds the reference's system}
//
// DirectAddressAssembler adds the cells' contributions at precomputed
// addresses in the Epetra value arrays; SystemAssembler, the reference,
// adds them through AffineConstraints::distribute_local_to_global(). Both
// run the same cell integrals (HyperelasticSolid::cell_contribution() on
// the same CellGeometry) on the same input values, so the cells' matrices
// and vectors are the same numbers in both, and what may differ is only
// the order in which an entry's terms are added: the order of the cells,
// the two halves of the fast serial residual, and the sums that the
// processes exchange at the interfaces.
//
// The test builds a distorted box clamped at x = 0 with a damping
// coefficient, takes a random displacement with strains of about 10 % and
// a random velocity, and assembles with both classes: the tangent, the
// damping matrix (the second matrix), the internal force and, as second
// force vector, the cells' damping forces $\mathbf C_e\mathbf v_e$ (from
// the second input vector), once with the matrices and once the vectors
// alone (the residual, which the fast class adds in a path of its own).
// DirectAddressAssembler::create() must have returned the fast class: with
// the reference on both sides the test could not fail. It does so in 1D, 2D and 3D, with linear and quadratic elements
// on hypercubes and on simplices, with the displacement and (in 3D) the
// mean-dilatation formulation, serially and under `mpiexec -n 2` and
// `-n 3` (tests/CMakeLists.txt).
//
// The tolerance is that of a reordered sum. An entry $s = \sum_{k=1}^n
// x_k$ of $n$ cell terms, added in any order or grouping, is computed with
// an error of at most $\gamma_{n-1}\sum_k|x_k|$, $\gamma_m = mu/(1 - mu)$,
// $u = 2^{-53}$ (Higham, Accuracy and Stability of Numerical Algorithms,
// section 4.2), so two orders differ by at most $2\gamma_{n-1}
// \sum_k|x_k|$. The test assembles, with the reference class, the number
// $n$ of terms of every entry (each cell entry replaced by one) and their
// magnitude $\sum_k|x_k|$ (each replaced by its absolute value), and
// checks every entry against this bound; and, relative to the largest
// entry, the largest difference against $2\gamma_{n-1}$ times the largest
// magnitude, with the largest $n$. An entry of a single term must agree
// exactly. The strain energy is a sum over all cells of nonnegative
// terms, so its relative tolerance is $2\gamma_{N-1}$ with N the number of
// cells; the smallest $\det\mathbf F$ is a minimum and must agree exactly.

#include "solver_test_tools.h"

#include <assembly/direct_address_assembler.h>
#include <assembly/system_assembler.h>
#include <cmath>
#include <core/soft_robot_dynamics.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <gtest/gtest.h>
#include <limits>
#include <random>

using namespace dealii;
using namespace SoftRobot;
using namespace SoftRobot::Testing;

template <typename T>
class SystemAssemblerTest : public ::testing::Test
{
};
TYPED_TEST_SUITE(SystemAssemblerTest, Dimensions);

namespace
{
  // The unit roundoff of double precision, and $\gamma_m$ (not `gamma`,
  // which the C library declares).
  constexpr double unit_roundoff = 0.5 * std::numeric_limits<double>::epsilon();

  double
  summation_gamma(const double m)
  {
    return m * unit_roundoff / (1. - m * unit_roundoff);
  }

  // A box of length 4 and width 1, clamped at x = 0, of one damped
  // material, with its interior vertices moved at random: 4 x 2 x 2
  // hexahedra, or 2 x 1 x 1 hexahedra each cut into simplices (48
  // tetrahedra in 3D), of degree p in the given volumetric formulation.
  // Each of three processes gets several cells.
  Parameters::AllParameters
  damped_box(const unsigned int dim,
             const bool         simplices,
             const unsigned int degree,
             const std::string &formulation)
  {
    std::ostringstream sections;
    sections
      << "subsection Geometry\n  set Generator = subdivided_hyper_rectangle\n"
      << "  set Generator arguments = "
      << box_arguments(dim, simplices ? 2 : 4, simplices ? 1 : 2, 4., 1.)
      << "\n  set Random distortion = 0.15\n"
      << "  set Convert to simplices = " << (simplices ? "true" : "false")
      << "\nend\n"
      << "subsection Finite element\n  set Polynomial degree = " << degree
      << "\n  set Volumetric formulation = " << formulation << "\nend\n"
      << "subsection Material 1\n  set Name = silicone\n"
      << "  set Shear modulus = 10\n  set Bulk modulus = 1000\n"
      << "  set Density = 1e-6\n  set Damping coefficient = 1e-3\nend\n"
      // The damping matrix of the state itself, which the cell integral
      // computes without a recorded viscosity (the Kelvin-Voigt damping
      // needs the viscosity of the step's first state, which the
      // simulator records; this file compares the global additions).
      << "subsection Damping\n"
      << "  set Stiffness-proportional damping = lagged matrix\nend\n"
      << "subsection Loads and constraints\n  set Fixed components = 0: "
      << std::string("xyz").substr(0, dim) << "\nend\n";
    Parameters::AllParameters parameters;
    parameters.read_string(parameter_text(dim, sections.str()));
    return parameters;
  }

  // A vector of random values in [-amplitude, amplitude] (fixed seed), zero
  // at the constrained dofs. The values are drawn for every global dof on
  // every process, so that the vector does not depend on the partition of
  // a given numbering.
  template <int dim>
  TrilinosWrappers::MPI::Vector
  partition_independent_random_vector(const Simulation<dim> &body,
                                      const double           amplitude,
                                      const unsigned int     seed)
  {
    TrilinosWrappers::MPI::Vector    u(body.displacement());
    const IndexSet                  &owned = u.locally_owned_elements();
    std::mt19937                     generator(seed);
    std::uniform_real_distribution<> uniform(-amplitude, amplitude);
    for (types::global_dof_index i = 0; i < u.size(); ++i)
      {
        const double value = uniform(generator);
        if (owned.is_element(i))
          u[i] = body.get_constraints().is_constrained(i) ? 0. : value;
      }
    u.compress(VectorOperation::insert);
    return u;
  }

  // What the cell integral hands to the global addition: its entries, their
  // magnitudes, or ones (so that the assembled entry counts its terms).
  enum class Entries
  {
    values,
    magnitudes,
    counts
  };

  // HyperelasticSolid's integral over the cell, and, as second force
  // vector, the cell's damping force $\mathbf C_e\mathbf v_e$ with the
  // cell's values of the second input vector. When the assembly asks for
  // the vectors alone, the cell's damping matrix comes from a second
  // integral with the matrices, and the force from the integral without
  // them, as in the program's residuals.
  template <int dim>
  typename SystemAssembler<dim>::LocalIntegrator
  integrator(const HyperelasticSolid<dim> &solid, const Entries entries)
  {
    return [&solid, entries](CellContribution<dim> &local) {
      const unsigned int n = local.force.size();
      solid.cell_contribution(local);
      if (local.request.second_force)
        {
          CellContribution<dim>     with_matrices;
          const FullMatrix<double> *damping = &local.second_matrix;
          if (!local.request.second_matrix)
            {
              with_matrices                       = local;
              with_matrices.request.matrix        = true;
              with_matrices.request.second_matrix = true;
              with_matrices.reset(n);
              solid.cell_contribution(with_matrices);
              damping = &with_matrices.second_matrix;
            }
          for (unsigned int i = 0; i < n; ++i)
            {
              double sum = 0.;
              for (unsigned int j = 0; j < n; ++j)
                sum += (*damping)(i, j) * local.input_values[1][j];
              local.second_force(i) = sum;
            }
        }
      if (entries == Entries::values)
        return;
      const auto replace = [entries](double &x) {
        x = (entries == Entries::magnitudes) ? std::abs(x) : 1.;
      };
      for (unsigned int i = 0; i < n; ++i)
        {
          replace(local.force(i));
          if (local.request.second_force)
            replace(local.second_force(i));
          for (unsigned int j = 0; j < n; ++j)
            {
              if (local.request.matrix)
                replace(local.matrix(i, j));
              if (local.request.second_matrix)
                replace(local.second_matrix(i, j));
            }
        }
    };
  }

  // The global objects of one assembler, in the layout of the simulator's
  // matrices and vectors: the tangent, damping matrix, internal and
  // damping force of the assembly with the matrices, and the two force
  // vectors of the assembly of the vectors alone.
  struct System
  {
    System(const TrilinosWrappers::SparseMatrix &layout,
           const TrilinosWrappers::MPI::Vector  &vector)
      : force(vector)
      , damping_force(vector)
      , residual(vector)
      , residual_damping_force(vector)
    {
      tangent.reinit(layout);
      damping.reinit(layout);
    }

    TrilinosWrappers::SparseMatrix tangent, damping;
    TrilinosWrappers::MPI::Vector  force, damping_force, residual,
      residual_damping_force;
    AssemblyResult with_matrices, residual_only;
  };

  template <int dim>
  void
  assemble(SystemAssembler<dim>                &assembler,
           const HyperelasticSolid<dim>        &solid,
           const Entries                        entries,
           const TrilinosWrappers::MPI::Vector &u,
           const TrilinosWrappers::MPI::Vector &v,
           System                              &system)
  {
    AssemblyRequest everything;
    everything.matrix        = true;
    everything.second_matrix = true;
    everything.second_force  = true;
    typename SystemAssembler<dim>::Targets targets;
    targets.force         = &system.force;
    targets.second_force  = &system.damping_force;
    targets.matrix        = &system.tangent;
    targets.second_matrix = &system.damping;
    system.with_matrices  = assembler.assemble(integrator(solid, entries),
                                              {&u, &v},
                                              everything,
                                              targets);

    AssemblyRequest residual;
    residual.second_force = true;
    targets               = {};
    targets.force         = &system.residual;
    targets.second_force  = &system.residual_damping_force;
    system.residual_only  = assembler.assemble(integrator(solid, entries),
                                              {&u, &v},
                                              residual,
                                              targets);
  }

  // The differences between the fast and the reference object, entry by
  // entry: the largest, the largest entry of the reference, and the bounds
  // of the reordered sums (see the top of the file), over all processes.
  struct Comparison
  {
    double largest_difference = 0.;
    double largest_entry      = 0.;
    double largest_magnitude  = 0.;
    double most_terms         = 0.;
    // The largest ratio of a difference to its own bound $2\gamma_{n-1}
    // \sum_k|x_k|$ (infinite if an entry of one term differs).
    double largest_bound_ratio = 0.;

    void
    add(const double fast,
        const double reference,
        const double magnitude,
        const double terms)
    {
      const double difference = std::abs(fast - reference);
      largest_difference      = std::max(largest_difference, difference);
      largest_entry           = std::max(largest_entry, std::abs(reference));
      largest_magnitude       = std::max(largest_magnitude, magnitude);
      most_terms              = std::max(most_terms, terms);
      if (difference > 0.)
        largest_bound_ratio =
          std::max(largest_bound_ratio,
                   (terms > 1.)
                     ? difference /
                         (2. * summation_gamma(terms - 1.) * magnitude)
                     : std::numeric_limits<double>::infinity());
    }

    void
    reduce(const MPI_Comm mpi_communicator)
    {
      for (double *value : {&largest_difference,
                            &largest_entry,
                            &largest_magnitude,
                            &most_terms,
                            &largest_bound_ratio})
        *value = Utilities::MPI::max(*value, mpi_communicator);
    }

    // The tolerance relative to the largest entry.
    double
    tolerance() const
    {
      return 2. * summation_gamma(most_terms - 1.) * largest_magnitude /
             largest_entry;
    }

    double
    relative_difference() const
    {
      return largest_difference / largest_entry;
    }
  };

  Comparison
  compare(const TrilinosWrappers::SparseMatrix &fast,
          const TrilinosWrappers::SparseMatrix &reference,
          const TrilinosWrappers::SparseMatrix &magnitudes,
          const TrilinosWrappers::SparseMatrix &counts,
          const MPI_Comm                        mpi_communicator)
  {
    Comparison comparison;
    for (const types::global_dof_index row :
         reference.locally_owned_range_indices())
      {
        auto a = fast.begin(row), b = reference.begin(row),
             s = magnitudes.begin(row), n = counts.begin(row);
        for (; b != reference.end(row); ++a, ++b, ++s, ++n)
          {
            EXPECT_TRUE(a->column() == b->column() &&
                        s->column() == b->column() &&
                        n->column() == b->column())
              << "the matrices' layouts differ in row " << row;
            comparison.add(a->value(), b->value(), s->value(), n->value());
          }
        EXPECT_TRUE(a == fast.end(row));
      }
    comparison.reduce(mpi_communicator);
    return comparison;
  }

  Comparison
  compare(const TrilinosWrappers::MPI::Vector &fast,
          const TrilinosWrappers::MPI::Vector &reference,
          const TrilinosWrappers::MPI::Vector &magnitudes,
          const TrilinosWrappers::MPI::Vector &counts,
          const MPI_Comm                       mpi_communicator)
  {
    Comparison comparison;
    for (const types::global_dof_index i : reference.locally_owned_elements())
      comparison.add(fast[i], reference[i], magnitudes[i], counts[i]);
    comparison.reduce(mpi_communicator);
    return comparison;
  }

  template <int dim>
  void
  check_assemblers(const bool         simplices,
                   const unsigned int degree,
                   const std::string &formulation)
  {
    const MPI_Comm  mpi_communicator = MPI_COMM_WORLD;
    Simulation<dim> body(damped_box(dim, simplices, degree, formulation),
                         mpi_communicator);
    body.make_grid();
    body.setup_system();
    const HyperelasticSolid<dim> &solid    = body.get_solid();
    const CellGeometry<dim>      &geometry = body.get_cell_geometry();
    ASSERT_TRUE(solid.has_damping());

    // Strains of about 10 %: the nodal displacements differ by up to twice
    // the amplitude between nodes whose distance is about the cell size
    // over the degree (0.5 to 1 for the hexahedra, about half of that for
    // the simplices).
    const double amplitude = (simplices ? 0.015 : 0.03) / degree;
    const TrilinosWrappers::MPI::Vector u =
      partition_independent_random_vector(body, amplitude, 1);
    const TrilinosWrappers::MPI::Vector v =
      partition_independent_random_vector(body, 1., 2);

    const IndexSet owned = body.get_dof_handler().locally_owned_dofs();
    IndexSet       relevant;
    DoFTools::extract_locally_relevant_dofs(body.get_dof_handler(), relevant);

    // The fast assembler's addresses are those of its own target matrices;
    // the reference's matrices have the same layout.
    System fast(body.mass_matrix(), u), reference(body.mass_matrix(), u),
      magnitudes(body.mass_matrix(), u), counts(body.mass_matrix(), u);
    const auto fast_assembler =
      DirectAddressAssembler<dim>::create(geometry,
                                          body.get_constraints(),
                                          owned,
                                          relevant,
                                          fast.tangent,
                                          &fast.damping,
                                          u,
                                          mpi_communicator);
    SystemAssembler<dim> reference_assembler(
      geometry, body.get_constraints(), owned, relevant, mpi_communicator);
    ASSERT_TRUE(fast_assembler->uses_direct_addresses())
      << "the homogeneous constraints should allow the fast assembler";
    ASSERT_FALSE(reference_assembler.uses_direct_addresses());

    assemble(*fast_assembler, solid, Entries::values, u, v, fast);
    assemble(reference_assembler, solid, Entries::values, u, v, reference);
    assemble(reference_assembler, solid, Entries::magnitudes, u, v, magnitudes);
    assemble(reference_assembler, solid, Entries::counts, u, v, counts);

    const std::vector<std::pair<std::string, Comparison>> comparisons = {
      {"tangent",
       compare(fast.tangent,
               reference.tangent,
               magnitudes.tangent,
               counts.tangent,
               mpi_communicator)},
      {"damping matrix",
       compare(fast.damping,
               reference.damping,
               magnitudes.damping,
               counts.damping,
               mpi_communicator)},
      {"internal force",
       compare(fast.force,
               reference.force,
               magnitudes.force,
               counts.force,
               mpi_communicator)},
      {"damping force",
       compare(fast.damping_force,
               reference.damping_force,
               magnitudes.damping_force,
               counts.damping_force,
               mpi_communicator)},
      {"internal force (vectors alone)",
       compare(fast.residual,
               reference.residual,
               magnitudes.residual,
               counts.residual,
               mpi_communicator)},
      {"damping force (vectors alone)",
       compare(fast.residual_damping_force,
               reference.residual_damping_force,
               magnitudes.residual_damping_force,
               counts.residual_damping_force,
               mpi_communicator)}};

    std::ostringstream report;
    report << dim << "D, " << (simplices ? "simplices" : "hypercubes")
           << ", p = " << degree << ", " << formulation << ", "
           << Utilities::MPI::n_mpi_processes(mpi_communicator)
           << " process(es):";
    for (const auto &[name, comparison] : comparisons)
      {
        report << "\n  " << name << ": largest difference "
               << comparison.relative_difference()
               << " of the largest entry (tolerance " << comparison.tolerance()
               << ", at most " << comparison.most_terms << " terms), "
               << comparison.largest_bound_ratio << " of the entry's own bound";
        // Something must have been assembled, or the comparison is void.
        EXPECT_GT(comparison.largest_entry, 0.) << name;
        EXPECT_LE(comparison.relative_difference(), comparison.tolerance())
          << name;
        EXPECT_LE(comparison.largest_bound_ratio, 1.) << name;
      }

    const double n_cells =
      Utilities::MPI::sum(static_cast<double>(geometry.n_cells),
                          mpi_communicator);
    for (const auto &[fast_result, reference_result] :
         {std::make_pair(fast.with_matrices, reference.with_matrices),
          std::make_pair(fast.residual_only, reference.residual_only)})
      {
        EXPECT_GT(reference_result.strain_energy, 0.);
        EXPECT_NEAR(fast_result.strain_energy,
                    reference_result.strain_energy,
                    2. * summation_gamma(n_cells - 1.) *
                      reference_result.strain_energy);
        EXPECT_EQ(fast_result.min_jacobian, reference_result.min_jacobian);
        EXPECT_FALSE(fast_result.inverted_point_found);
        EXPECT_FALSE(reference_result.inverted_point_found);
      }
    report << "\n  strain energy " << reference.with_matrices.strain_energy
           << ", difference "
           << std::abs(fast.with_matrices.strain_energy -
                       reference.with_matrices.strain_energy) /
                reference.with_matrices.strain_energy
           << " (residual alone "
           << std::abs(fast.residual_only.strain_energy -
                       reference.residual_only.strain_energy) /
                reference.residual_only.strain_energy
           << ", tolerance " << 2. * summation_gamma(n_cells - 1.)
           << "); smallest det F " << reference.with_matrices.min_jacobian;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::cout << report.str() << std::endl;
  }
} // namespace



TYPED_TEST(SystemAssemblerTest, FastAssemblerBuildsTheReferenceSystem)
{
  constexpr int dim = TypeParam::value;
  // In 1D a simplex is a line, the same cell as the hypercube.
  const std::vector<bool> cell_kinds =
    (dim == 1) ? std::vector<bool>{false} : std::vector<bool>{false, true};
  for (const bool simplices : cell_kinds)
    for (const unsigned int degree : {1u, 2u})
      {
        check_assemblers<dim>(simplices, degree, "displacement");
        // The mean-dilatation formulation exists in 3D only.
        if constexpr (dim == 3)
          check_assemblers<dim>(simplices, degree, "mean dilatation");
      }
}
