#pragma once

#include <string>
#include <type_traits>
#include <variant>

#include <boost/program_options.hpp>

#include "mrs_vpr/parameters.hpp"
#include "tool_main.hpp"

namespace mrs_vpr {
namespace tools {

/// The command-line option of a descriptor parameter: "descriptor/type" is --descriptor,
/// "descriptor/image_width" --image-width, "descriptor/hog/cell_size" --hog-cell-size.
inline std::string descriptorOption(const std::string& parameter) {
  std::string name = parameter.substr(parameter.find('/') + 1);
  if (name == "type") return "descriptor";
  for (char& c : name) {
    if (c == '/' || c == '_') c = '-';
  }
  return name;
}

/// Adds an option for every parameter of the core's descriptor table, with the meaning it gives and
/// the value `params` holds as the default; the values land in `params`, which must outlive parsing.
/// `shown_default`, when given, is what --help shows as every default instead of the value.
inline void addDescriptorOptions(boost::program_options::options_description& description, DescriptorParams& params,
                                 const char* shown_default = nullptr) {
  for (const auto& spec : descriptorParameters()) {
    std::visit(
        [&](auto member) {
          using Value = std::decay_t<decltype(params.*member)>;
          if constexpr (std::is_same_v<Value, int> || std::is_same_v<Value, double> ||
                        std::is_same_v<Value, std::string>) {
            auto* value = boost::program_options::value(&(params.*member));
            value = shown_default == nullptr ? value->default_value(params.*member)
                                             : value->default_value(params.*member, shown_default);
            description.add_options()(descriptorOption(spec.info.name).c_str(), value, spec.info.meaning.c_str());
          }
        },
        spec.member);
  }
}

/// Whether the command line set any descriptor option (rather than leaving every default).
inline bool descriptorOptionsGiven(const boost::program_options::variables_map& variables) {
  for (const auto& spec : descriptorParameters()) {
    if (givenOnCommandLine(variables, descriptorOption(spec.info.name))) return true;
  }
  return false;
}

/// Throws when the command line sets an option of the front end it does not use (--image-width with
/// HOG, --hog-cell-size with the thumbnail), which would otherwise be ignored without a word.
inline void refuseOtherFrontEndsOptions(const boost::program_options::variables_map& variables,
                                        const DescriptorParams& params) {
  for (const auto& spec : descriptorParameters()) {
    const std::string& name = spec.info.name;
    if (!givenOnCommandLine(variables, descriptorOption(name))) continue;
    const std::string owner = frontEndOwning(name);
    if (!owner.empty() && owner != params.type) {
      throw boost::program_options::error("--" + descriptorOption(name) + " is an option of the " + owner +
                                          " front end, and the front end is " + params.type + " (add --descriptor " +
                                          owner + ")");
    }
  }
}

}  // namespace tools
}  // namespace mrs_vpr
