#pragma once

// The benchmarks' command line: the tools' parser (src/tools/tool_main.hpp), which also refuses a word
// that is no option. Boost.Program_options drops such words silently, so "--lengths 100 200" would
// run with 100 alone.

#include <string>

#include <boost/program_options.hpp>

#include "tools/tool_main.hpp"

namespace mrs_vpr {
namespace benchmark {

/// As tools::parseCommandLine (false after printing the help), but a word that belongs to no option
/// is an error that names it.
inline bool parseCommandLine(int argc, char** argv, const char* usage,
                             const boost::program_options::options_description& options,
                             boost::program_options::variables_map& variables) {
  namespace po = boost::program_options;
  const po::parsed_options parsed = po::command_line_parser(argc, argv).options(options).run();
  for (const po::option& option : parsed.options) {
    if (option.string_key.empty() && !option.original_tokens.empty()) {
      throw po::error("unexpected argument '" + option.original_tokens.front() + "'");
    }
  }
  return tools::parseCommandLine(argc, argv, usage, options, variables);
}

}  // namespace benchmark
}  // namespace mrs_vpr
