// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The BLAS kernels for this processor}
//
// See include/solvers/blas_kernels.h.

#include <cstdlib>
#include <dlfcn.h>
#include <solvers/blas_kernels.h>

namespace SoftRobot
{
  namespace BlasKernels
  {
    namespace
    {
      // An OpenBLAS function, or nullptr if no library of the process
      // defines it.
      template <typename Function>
      Function *
      openblas_function(const char *name)
      {
        return reinterpret_cast<Function *>(dlsym(RTLD_DEFAULT, name));
      }
    } // namespace



    // GCC's built-ins read the processor's feature flags and count the
    // AVX and AVX-512 instructions only where the operating system saves
    // their registers.
    ProcessorFeatures
    ProcessorFeatures::of_this_processor()
    {
      ProcessorFeatures features;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
      __builtin_cpu_init();
      features.avx2_fma =
        __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
      features.avx512 = features.avx2_fma &&
                        __builtin_cpu_supports("avx512f") &&
                        __builtin_cpu_supports("avx512cd") &&
                        __builtin_cpu_supports("avx512bw") &&
                        __builtin_cpu_supports("avx512dq") &&
                        __builtin_cpu_supports("avx512vl");
#endif
      return features;
    }



    std::string
    replacement(const std::string       &library_choice,
                const char              *user_setting,
                const ProcessorFeatures &features)
    {
      if (user_setting != nullptr && *user_setting != '\0')
        return "";
      if (library_choice != "Prescott")
        return "";
      if (features.avx512)
        return "SkylakeX";
      if (features.avx2_fma)
        return "Haswell";
      return "";
    }



    std::string
    in_use()
    {
      const auto corename =
        openblas_function<char *()>("openblas_get_corename");
      if (corename == nullptr)
        return "";
      const char *name = corename();
      return name != nullptr ? name : "";
    }



    // gotoblas_dynamic_quit() forgets the kernels, gotoblas_dynamic_init()
    // chooses them again, reading OPENBLAS_CORETYPE as at the library's
    // loading. A build of OpenBLAS for one processor only has neither.
    Selection
    select()
    {
      Selection selection;
      selection.library_choice = in_use();
      selection.in_use         = selection.library_choice;
      const std::string wanted =
        replacement(selection.library_choice,
                    std::getenv("OPENBLAS_CORETYPE"),
                    ProcessorFeatures::of_this_processor());
      const auto quit = openblas_function<void()>("gotoblas_dynamic_quit");
      const auto init = openblas_function<void()>("gotoblas_dynamic_init");
      if (wanted.empty() || quit == nullptr || init == nullptr)
        return selection;
      // Unset or empty here (replacement() keeps any other value).
      setenv("OPENBLAS_CORETYPE", wanted.c_str(), /*overwrite=*/1);
      quit();
      init();
      selection.in_use = in_use();
      return selection;
    }
  } // namespace BlasKernels
} // namespace SoftRobot
