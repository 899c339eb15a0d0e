// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Functions from the expressions of the parameter file}
//
// Initial fields and tractions are muparser expressions with one component
// per space dimension, separated by semicolons, in the variables `x`, `y`,
// `z` (as many as the dimension) and `t`, with the constants of `Loads and
// constraints/Function constants`. An empty expression means zero.
//
// Implemented in source/core/expression_function.cc.

#ifndef soft_robot_core_expression_function_h
#define soft_robot_core_expression_function_h

#include <deal.II/base/function_parser.h>
#include <map>
#include <string>

namespace SoftRobot
{
  using namespace dealii;

  // Sets up `function` (with dim components) from `expression`; errors name
  // the entry.
  template <int dim>
  void
  initialize_vector_function(FunctionParser<dim> &function,
                             const std::string   &expression,
                             const std::string   &constants,
                             const std::string   &entry_name);

  // The constants 'a=1, b=2' as a map.
  std::map<std::string, double>
  parse_constants(const std::string &text);
} // namespace SoftRobot

#endif
