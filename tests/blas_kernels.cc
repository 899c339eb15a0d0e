// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Tests of the choice of the BLAS kernels}
//
// BlasKernels (solvers/blas_kernels.h) replaces OpenBLAS's generic kernels
// by those of the processor's instructions. The decision is checked on its
// own, for every combination that matters; its effect on the OpenBLAS this
// test runs with: after select() the library must use the kernels decided
// for this processor, and products of matrices in both precisions must
// still be right with them. Each test is a process of its own (ctest), so
// OpenBLAS starts each with the kernels it chose itself.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deal.II/lac/lapack_templates.h>
#include <gtest/gtest.h>
#include <iostream>
#include <limits>
#include <solvers/blas_kernels.h>
#include <string>
#include <vector>

using namespace SoftRobot;

namespace
{
  BlasKernels::ProcessorFeatures
  features(const bool avx2_fma, const bool avx512)
  {
    BlasKernels::ProcessorFeatures result;
    result.avx2_fma = avx2_fma;
    result.avx512   = avx512;
    return result;
  }

  // The largest difference between OpenBLAS's gemm and the sums written
  // out, relative to the largest entry, for a product of two n x n
  // matrices (large enough for the library's blocked kernels).
  template <typename Number>
  double
  gemm_error(const int n)
  {
    std::vector<Number> a(n * n), b(n * n), c(n * n, 0.);
    for (int i = 0; i < n * n; ++i)
      {
        a[i] = std::sin(0.37 * (i + 1.));
        b[i] = std::cos(0.91 * (i + 1.));
      }
    const Number one = 1., zero = 0.;
    dealii::gemm("N",
                 "N",
                 &n,
                 &n,
                 &n,
                 &one,
                 a.data(),
                 &n,
                 b.data(),
                 &n,
                 &zero,
                 c.data(),
                 &n);
    double difference = 0., size = 0.;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        {
          double sum = 0.;
          for (int l = 0; l < n; ++l)
            sum += double(a[i + l * n]) * double(b[l + j * n]);
          difference = std::max(difference, std::abs(c[i + j * n] - sum));
          size       = std::max(size, std::abs(sum));
        }
    return difference / size;
  }
} // namespace

TEST(BlasKernelsTest, ReplacesOnlyTheGenericKernelsOnCapableProcessors)
{
  const auto none = features(false, false), avx2 = features(true, false),
             avx512 = features(true, true);
  EXPECT_EQ(BlasKernels::replacement("Prescott", nullptr, avx512), "SkylakeX");
  EXPECT_EQ(BlasKernels::replacement("Prescott", nullptr, avx2), "Haswell");
  EXPECT_EQ(BlasKernels::replacement("Prescott", "", avx2), "Haswell");
  // The generic kernels are all an older processor can run.
  EXPECT_EQ(BlasKernels::replacement("Prescott", nullptr, none), "");
  // OpenBLAS's own choice of specific kernels is kept.
  EXPECT_EQ(BlasKernels::replacement("Haswell", nullptr, avx512), "");
  EXPECT_EQ(BlasKernels::replacement("Zen", nullptr, avx2), "");
  // Not OpenBLAS.
  EXPECT_EQ(BlasKernels::replacement("", nullptr, avx512), "");
  // The user's choice, also of the generic kernels.
  EXPECT_EQ(BlasKernels::replacement("Prescott", "Prescott", avx512), "");
  EXPECT_EQ(BlasKernels::replacement("Prescott", "Haswell", avx512), "");
}

TEST(BlasKernelsTest, SelectsTheDecidedKernelsAndTheyMultiplyRight)
{
  const std::string library_choice = BlasKernels::in_use();
  if (library_choice.empty())
    GTEST_SKIP() << "the BLAS in use is not OpenBLAS";
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr)
    GTEST_SKIP() << "OPENBLAS_CORETYPE is set: the kernels are the user's";
  const std::string wanted = BlasKernels::replacement(
    library_choice,
    nullptr,
    BlasKernels::ProcessorFeatures::of_this_processor());

  const BlasKernels::Selection selection = BlasKernels::select();
  EXPECT_EQ(selection.library_choice, library_choice);
  EXPECT_EQ(selection.in_use, wanted.empty() ? library_choice : wanted);
  EXPECT_EQ(BlasKernels::in_use(), selection.in_use);
  EXPECT_EQ(selection.changed(), !wanted.empty());

  const double error_double = gemm_error<double>(96);
  const double error_float  = gemm_error<float>(96);
  EXPECT_LT(error_double, 100. * std::numeric_limits<double>::epsilon());
  EXPECT_LT(error_float, 100. * std::numeric_limits<float>::epsilon());
  RecordProperty("kernels", selection.in_use);
  std::cout << "kernels: " << selection.library_choice << " -> "
            << selection.in_use << "; gemm errors " << error_double << ", "
            << error_float << std::endl;
}
