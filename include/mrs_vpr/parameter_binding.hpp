#pragma once

// The parameter tables (parameters.hpp) bound to where their values lie in a struct of parameter
// groups, so that whatever reads or lists parameters by name (the node's loader and --help, the Python
// API) is built from the tables and takes a parameter added there without a change.

#include <functional>
#include <variant>
#include <vector>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/// A parameter's field, whichever type it has.
using ParameterField = std::variant<int*, double*, std::uint64_t*, WindowAlignment*, std::string*>;

/// One parameter of a table: its description, and its field in a `Root`.
template <typename Root>
struct ParameterBinding {
  const ParameterInfo* info;
  std::function<ParameterField(Root&)> field;
};

/// Appends to `bindings` one binding for each of `specs`, whose group `select` finds in a Root.
template <typename Root, typename Group, typename Select>
void bindParameters(std::vector<ParameterBinding<Root>>& bindings, const std::vector<ParameterSpec<Group>>& specs,
                    Select select) {
  for (const auto& spec : specs) {
    bindings.push_back({&spec.info, [member = spec.member, select](Root& root) {
                          return std::visit([&](auto m) -> ParameterField { return &(select(root).*m); }, member);
                        }});
  }
}

/// Every parameter of the core, in the order of the parameter reference, bound into a Root whose
/// members `core` (Parameters) and `recognizer` (RecognizerParams) hold them.
template <typename Root>
std::vector<ParameterBinding<Root>> coreParameterBindings() {
  std::vector<ParameterBinding<Root>> bindings;
  bindParameters(bindings, descriptorParameters(),
                 [](Root& root) -> DescriptorParams& { return root.core.descriptor; });
  bindParameters(bindings, sequenceParameters(), [](Root& root) -> SequenceParams& { return root.core.sequence; });
  bindParameters(bindings, mrsParameters(), [](Root& root) -> MrsParams& { return root.core.mrs; });
  bindParameters(bindings, recognizerParameters(), [](Root& root) -> RecognizerParams& { return root.recognizer; });
  return bindings;
}

}  // namespace mrs_vpr
