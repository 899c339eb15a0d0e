// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The dimensions the program is instantiated for}
//
// Every class template of the program is defined in a source file and
// instantiated there for the dimensions listed here, and only here: a
// source file defines a macro that instantiates its templates for one
// dimension and passes it to SOFT_ROBOT_FOR_EACH_DIMENSION.
//
// @code
// #define SOFT_ROBOT_INSTANTIATE(dim) template class Foo<dim>;
//   SOFT_ROBOT_FOR_EACH_DIMENSION(SOFT_ROBOT_INSTANTIATE)
// #undef SOFT_ROBOT_INSTANTIATE
// @endcode

#ifndef soft_robot_core_config_h
#define soft_robot_core_config_h

#define SOFT_ROBOT_FOR_EACH_DIMENSION(macro) macro(1) macro(2) macro(3)

#endif
