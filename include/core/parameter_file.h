// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Reading a parameter file}
//
// ParameterHandler reads `include` statements itself, but resolves the file
// they name against the working directory, and only the parameter file
// given on the command line had its includes rewritten to be relative to
// it: an `include` inside an included file resolved against the working
// directory. And its messages name the line of whatever text it was given,
// not the subsection, and spread over several lines.
//
// The program therefore reads a parameter file itself, before
// ParameterHandler sees it: every `include` is replaced by the lines of the
// file it names, resolved against the directory of the file that holds the
// statement (so a scene runs from any working directory, and a library of
// shared entries can include another one next to it), recursively, with a
// check for a file that includes itself. The text handed to
// ParameterHandler is the expanded one; for each of its lines the program
// remembers the file and line it came from and the subsection it stands in,
// so that a message of ParameterHandler's ("Line <17> of file <...>") is
// turned into one line that names the file the user wrote, the line there,
// the subsection, the entry, the value and the allowed range.
//
// Implemented in source/core/parameter_file.cc.

#ifndef soft_robot_core_parameter_file_h
#define soft_robot_core_parameter_file_h

#include <string>
#include <vector>

namespace SoftRobot
{
  namespace Parameters
  {
    class ParameterFileText
    {
    public:
      // Reads `filename` and the files it includes; throws with a message
      // naming the file and line of an `include` that cannot be read.
      explicit ParameterFileText(const std::string &filename);

      // The text with every include expanded.
      const std::string &
      text() const
      {
        return expanded;
      }

      // A message of ParameterHandler about this text, as one line that
      // names the original file, line and subsection.
      std::string
      locate(const std::string &message) const;

    private:
      struct Origin
      {
        std::string  file;
        unsigned int line;
        std::string  subsection;
      };

      // Appends the lines of `filename`; `chain` holds the files that
      // include it, `subsections` the subsection path at its first line.
      void
      expand(const std::string        &filename,
             std::vector<std::string> &chain,
             std::vector<std::string> &subsections);

      std::string         expanded;
      std::vector<Origin> origins;
    };

    // The text with every run of white space (new lines among them)
    // replaced by one space, without leading or trailing space.
    std::string
    one_line(const std::string &text);
  } // namespace Parameters
} // namespace SoftRobot

#endif
