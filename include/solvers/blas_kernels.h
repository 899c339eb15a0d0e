// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The BLAS kernels for this processor}
//
// OpenBLAS is built for many processors at once and picks the kernels of
// the one it runs on when the library is loaded. A processor its version
// does not know gets the generic x86-64 kernels, named "Prescott", which
// use neither AVX2 nor AVX-512. Debian 12's OpenBLAS 0.3.21 does this on
// the Xeon of family 6, model 207 (it reports "Core: Prescott" with
// OPENBLAS_VERBOSE=2), and MUMPS's dense kernels (gemm, gemv, trsm in the
// fronts of the factor and in the back substitutions) then run slower than
// the processor allows (doc/performance_discussion.md, item 48, has the
// measurement).
//
// OpenBLAS's documented remedy is the environment variable
// OPENBLAS_CORETYPE, read when the library is loaded, so before main().
// select() does at the program's start what that variable would have done:
// if OpenBLAS reports its generic kernels although the processor has the
// AVX-512 instructions of its SkylakeX kernels (or AVX2 and FMA for its
// Haswell kernels), it sets the variable and has OpenBLAS choose its
// kernels again (through gotoblas_dynamic_quit() and
// gotoblas_dynamic_init(), exported by its library though not declared in
// its header). Nothing changes if the user set OPENBLAS_CORETYPE (the choice is
// then theirs, also to keep the generic kernels), if OpenBLAS chose
// kernels of its own, or if the program runs with another BLAS: all
// OpenBLAS functions are found through dlsym, none is linked by name.
//
// select() must run before the first BLAS call and before any thread that
// could make one: main() calls it first.
//
// Implemented in source/solvers/blas_kernels.cc.

#ifndef soft_robot_solvers_blas_kernels_h
#define soft_robot_solvers_blas_kernels_h

#include <string>

namespace SoftRobot
{
  namespace BlasKernels
  {
    // The instructions the kernels need, as the processor and the
    // operating system provide them.
    struct ProcessorFeatures
    {
      bool avx2_fma = false;
      // AVX-512 F, CD, BW, DQ and VL: the instructions of Skylake-SP.
      bool avx512 = false;

      static ProcessorFeatures
      of_this_processor();
    };

    // The kernels OpenBLAS should use instead of its choice `library_choice`
    // (its name for its kernels), or "" to keep it: the decision of select()
    // without its effect, for the tests. `user_setting` is the value of
    // OPENBLAS_CORETYPE, nullptr if it is not set.
    std::string
    replacement(const std::string       &library_choice,
                const char              *user_setting,
                const ProcessorFeatures &features);

    // The name of the kernels OpenBLAS uses, or "" if the BLAS the program
    // runs with is not OpenBLAS.
    std::string
    in_use();

    struct Selection
    {
      // OpenBLAS's own choice and the kernels in use after select(); both
      // "" without OpenBLAS, equal if nothing was changed.
      std::string library_choice;
      std::string in_use;

      bool
      changed() const
      {
        return library_choice != in_use;
      }
    };

    Selection
    select();
  } // namespace BlasKernels
} // namespace SoftRobot

#endif
