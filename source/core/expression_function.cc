// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Functions from the expressions of the parameter file}
//
// See include/core/expression_function.h.

#include <core/config.h>
#include <core/expression_function.h>
#include <deal.II/base/utilities.h>
#include <sstream>

namespace SoftRobot
{
  // @sect4{parse_constants}
  std::map<std::string, double>
  parse_constants(const std::string &text)
  {
    std::map<std::string, double> constants;
    for (const auto &entry : Utilities::split_string_list(text, ','))
      {
        const auto pair = Utilities::split_string_list(entry, '=');
        AssertThrow(pair.size() == 2,
                    ExcMessage("Loads and constraints/Function constants: "
                               "expected 'name=value', got '" +
                               entry + "'."));
        constants[pair[0]] = Utilities::string_to_double(pair[1]);
      }
    return constants;
  }



  // @sect4{initialize_vector_function}
  //
  // The variables are the coordinates and the time; the number of
  // components must be the dimension.
  template <int dim>
  void
  initialize_vector_function(FunctionParser<dim> &function,
                             const std::string   &expression,
                             const std::string   &constants,
                             const std::string   &entry_name)
  {
    std::string text = expression;
    if (text.empty())
      {
        text = "0";
        for (unsigned int d = 1; d < dim; ++d)
          text += "; 0";
      }
    const unsigned int n_components =
      Utilities::split_string_list(text, ';').size();
    AssertThrow(n_components == dim,
                ExcMessage(entry_name + " must have " + std::to_string(dim) +
                           " components separated by ';' in " +
                           std::to_string(dim) + "D, but '" + expression +
                           "' has " + std::to_string(n_components) + "."));
    try
      {
        function.initialize(FunctionParser<dim>::default_variable_names() +
                              ",t",
                            text,
                            parse_constants(constants),
                            /*time_dependent=*/true);
      }
    catch (ExceptionBase &error)
      {
        std::ostringstream reason;
        error.print_info(reason);
        AssertThrow(false,
                    ExcMessage(entry_name + ": cannot parse '" + expression +
                               "': " + reason.str()));
      }
  }



#define SOFT_ROBOT_INSTANTIATE(dim)                                    \
  template void initialize_vector_function<dim>(FunctionParser<dim> &, \
                                                const std::string &,   \
                                                const std::string &,   \
                                                const std::string &);
  SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
#undef SOFT_ROBOT_INSTANTIATE
} // namespace SoftRobot
