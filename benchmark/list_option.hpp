#pragma once

// A comma-separated list as one Boost.Program_options value ("--lengths 100,200,300"), shared by the
// benchmarks so that a bad item is refused as any bad value is: "the argument ('100,x') for option
// '--lengths' is invalid".

#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/any.hpp>
#include <boost/lexical_cast.hpp>
#include <boost/program_options.hpp>

namespace mrs_vpr {
namespace benchmark {

/// The items of a comma-separated option value; never empty, no empty item.
template <typename T>
struct ListOption {
  std::vector<T> items;
};

/// Prints the list as it is written on the command line (for the defaults that --help shows).
template <typename T>
std::ostream& operator<<(std::ostream& stream, const ListOption<T>& list) {
  for (std::size_t i = 0; i < list.items.size(); ++i) stream << (i > 0 ? "," : "") << list.items[i];
  return stream;
}

/// Found by Boost.Program_options through argument-dependent lookup: parses "a,b,c".
template <typename T>
void validate(boost::any& value, const std::vector<std::string>& tokens, ListOption<T>*, int) {
  namespace po = boost::program_options;
  po::validators::check_first_occurrence(value);
  const std::string& text = po::validators::get_single_string(tokens);
  ListOption<T> list;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (item.empty()) throw po::invalid_option_value(text);
    try {
      list.items.push_back(boost::lexical_cast<T>(item));
    } catch (const boost::bad_lexical_cast&) {
      throw po::invalid_option_value(text);
    }
  }
  // getline drops a trailing empty item: "1,2," would otherwise pass for "1,2".
  if (list.items.empty() || text.back() == ',') throw po::invalid_option_value(text);
  value = list;
}

/// An option value that fills `target` from a comma-separated list; `target`'s contents are the
/// default (shown by --help).
template <typename T>
boost::program_options::typed_value<ListOption<T>>* listValue(std::vector<T>* target) {
  return boost::program_options::value<ListOption<T>>()
      ->default_value(ListOption<T>{*target})
      ->notifier([target](const ListOption<T>& list) { *target = list.items; });
}

}  // namespace benchmark
}  // namespace mrs_vpr
