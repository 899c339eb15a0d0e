// SPDX-License-Identifier: LGPL-2.1-or-later

// @sect3{Reading a parameter file}
//
// See include/core/parameter_file.h.

#include <algorithm>
#include <core/parameter_file.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace SoftRobot
{
  namespace Parameters
  {
    using namespace dealii;

    std::string
    one_line(const std::string &text)
    {
      std::istringstream words(text);
      std::string        word, result;
      while (words >> word)
        result += (result.empty() ? "" : " ") + word;
      return result;
    }



    namespace
    {
      // The line without its comment (ParameterHandler's '#'), trimmed.
      std::string
      without_comment(const std::string &line)
      {
        return Utilities::trim(line.substr(0, line.find('#')));
      }

      std::string
      joined(const std::vector<std::string> &path)
      {
        std::string result;
        for (const std::string &name : path)
          result += (result.empty() ? "" : "/") + name;
        return result;
      }
    } // namespace



    ParameterFileText::ParameterFileText(const std::string &filename)
    {
      std::vector<std::string> chain, subsections;
      expand(filename, chain, subsections);
    }



    // @sect4{ParameterFileText::expand}
    //
    // The subsection path is followed as ParameterHandler follows it
    // ('subsection <name>' enters, 'end' leaves), only to name it in
    // messages: whether the statements are balanced and the subsections
    // exist is ParameterHandler's to check.
    void
    ParameterFileText::expand(const std::string        &filename,
                              std::vector<std::string> &chain,
                              std::vector<std::string> &subsections)
    {
      std::ifstream file(filename);
      AssertThrow(file,
                  ExcMessage(chain.empty()
                               ? "Cannot open the parameter file '" + filename +
                                   "'."
                               : "In the parameter file '" + chain.back() +
                                   "': cannot open the file '" + filename +
                                   "' that it includes (include statements are "
                                   "relative to the file that holds them)."));
      chain.push_back(filename);
      const std::filesystem::path directory =
        std::filesystem::path(filename).parent_path();
      std::string  line;
      unsigned int number = 0;
      while (std::getline(file, line))
        {
          ++number;
          const std::string  statement = without_comment(line);
          std::istringstream words(statement);
          std::string        keyword;
          words >> keyword;
          if (keyword == "include" || keyword == "INCLUDE")
            {
              const std::string name =
                Utilities::trim(statement.substr(keyword.size()));
              AssertThrow(!name.empty(),
                          ExcMessage("In the parameter file '" + filename +
                                     "', line " + std::to_string(number) +
                                     ": 'include' without a file name."));
              std::filesystem::path included(name);
              if (included.is_relative())
                included = directory / included;
              const std::string included_name = included.lexically_normal();
              AssertThrow(
                std::find(chain.begin(), chain.end(), included_name) ==
                  chain.end(),
                ExcMessage("In the parameter file '" + filename + "', line " +
                           std::to_string(number) + ": '" + included_name +
                           "' includes itself."));
              // The statement's own line stays (as a comment), so that the
              // expanded text has a line for it.
              expanded += "# " + line + '\n';
              origins.push_back({filename, number, joined(subsections)});
              expand(included_name, chain, subsections);
              continue;
            }
          if (keyword == "subsection")
            subsections.push_back(
              Utilities::trim(statement.substr(keyword.size())));
          else if (keyword == "end" && !subsections.empty())
            subsections.pop_back();
          expanded += line + '\n';
          origins.push_back({filename, number, joined(subsections)});
        }
      chain.pop_back();
    }



    // @sect4{ParameterFileText::locate}
    //
    // ParameterHandler's messages start with "Line <n> of file <name>:"
    // (one of them lacks the closing '>'); the rest says what is wrong.
    std::string
    ParameterFileText::locate(const std::string &message) const
    {
      static const std::regex position(
        "Line <([0-9]+)> of file <([^>]*?)>?:\\s*");
      std::smatch match;
      if (!std::regex_search(message, match, position))
        return one_line(message);
      const unsigned int line = std::stoul(match[1].str());
      std::string        reason =
        one_line(std::string(match.suffix().first, message.end()));
      if (line == 0 || line > origins.size())
        return one_line(message);
      const Origin &origin = origins[line - 1];
      return "In the parameter file '" + origin.file + "', line " +
             std::to_string(origin.line) +
             (origin.subsection.empty()
                ? std::string()
                : " (subsection '" + origin.subsection + "')") +
             ": " + reason;
    }
  } // namespace Parameters
} // namespace SoftRobot
