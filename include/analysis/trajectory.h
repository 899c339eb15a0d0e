// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{The tip trajectory as recorded}
//
// Implemented in source/analysis/trajectory.cc.
//
// A trajectory is a sequence of times and tip displacements, as the
// simulator writes it at the end of every time step and as motion-capture
// scripts export it. This header declares the record, the reader of its CSV
// form and the removal of an initial interval (e.g. an actuation phase
// before the free decay that is to be analysed).

#ifndef soft_robot_analysis_trajectory_h
#define soft_robot_analysis_trajectory_h

#include <array>
#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Analysis
  {
    // @sect4{The record}
    //
    // The $x$ axis is the actuator axis (vertical, gravity points along
    // $+x$); a planar or one-dimensional record has only the first one or
    // two displacement components, and <code>n_components</code> says how
    // many are meaningful (the others are zero).
    struct TipTrajectory
    {
      std::vector<double>                time;
      std::vector<std::array<double, 3>> displacement;
      unsigned int                       n_components = 1;
    };



    // @sect4{Reading a CSV file}
    //
    // Lines whose first non-blank character is <code>#</code> are comments,
    // blank lines are skipped. The first other line is a header of
    // comma-separated column names; the columns <code>t</code> and
    // <code>u_x</code> are required, <code>u_y</code> and then
    // <code>u_z</code> are optional, and all other columns (velocities,
    // energies, ...) are ignored. Times must increase strictly. Malformed
    // input throws std::runtime_error with a message that names the file,
    // the line and the column.
    TipTrajectory
    read_tip_trajectory(const std::string &csv_file);



    // @sect4{Skipping an initial interval}
    //
    // Drop the samples in the first <code>seconds</code> of the record.
    // Throws std::invalid_argument unless $0 \le$ <code>seconds</code> and
    // enough of the record (at least 16 samples) remains; the message gives
    // the allowed range.
    TipTrajectory
    skip_initial_interval(const TipTrajectory &trajectory,
                          const double         seconds);
  } // namespace Analysis
} // namespace SoftRobot

#endif
