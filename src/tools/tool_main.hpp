#pragma once

#include <initializer_list>
#include <iostream>
#include <string>

#include <boost/program_options.hpp>

#include "interruption.hpp"

namespace mrs_vpr {
namespace tools {

/// Parses the command line into `variables`. Returns false when --help was asked for: the usage
/// and the options have then been printed and the tool should exit 0. A word that belongs to no
/// option is an error that names it: Boost.Program_options would drop it silently, so that
/// "--lengths 100 200" would run with 100 alone.
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
  po::store(parsed, variables);
  if (variables.count("help") > 0) {
    std::cout << usage << "\n" << options << std::flush;
    return false;
  }
  boost::program_options::notify(variables);
  return true;
}

/// Whether the command line set `option` (its name without "--"), rather than leaving it out or at
/// its default.
inline bool givenOnCommandLine(const boost::program_options::variables_map& variables, const std::string& option) {
  const auto found = variables.find(option);
  return found != variables.end() && !found->second.defaulted();
}

/// Throws for each of `paths` (option names without "--") given as an empty string: an unset shell
/// variable, which the tool would otherwise read as the option left out (the identity ground truth,
/// no JSON written).
inline void refuseEmptyPaths(const boost::program_options::variables_map& variables,
                             std::initializer_list<const char*> paths) {
  for (const char* name : paths) {
    if (variables.count(name) > 0 && variables[name].as<std::string>().empty()) {
      throw boost::program_options::error(std::string("--") + name + " was given an empty path");
    }
  }
}

/// Runs a command-line tool's `run`, turning any exception into one line on stderr
/// ("<name>: error: ...") and exit code 1, so that bad input never ends in a crash or a stack dump;
/// an interruption (interruption.hpp) ends it with 128 + the signal's number.
template <typename Run>
int runTool(const char* name, Run&& run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const Interrupted& interruption) {
    std::cerr << name << ": " << interruption.what() << "; nothing unfinished was left behind" << std::endl;
    return 128 + interruption.signalNumber();
  } catch (const boost::program_options::error& error) {
    std::cerr << name << ": error: " << error.what() << " (see --help)" << std::endl;
  } catch (const std::exception& error) {
    std::string message = error.what();
    for (char& c : message) {
      if (c == '\n' || c == '\r') c = ' ';  // One line, whatever the source of the message.
    }
    std::cerr << name << ": error: " << message << std::endl;
  }
  return 1;
}

}  // namespace tools
}  // namespace mrs_vpr
