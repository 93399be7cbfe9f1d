// Parameters from and to Python: every entry of the core's tables, by its exact name.

#include "parameter_conversion.hpp"

#include <climits>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "mrs_vpr/parameter_binding.hpp"

namespace mrs_vpr {
namespace python {
namespace {

/// One parameter: its description in the core's tables and where its value goes.
using Entry = ParameterBinding<Settings>;

/// The core's tables in the order of the parameter reference; a parameter added there is accepted here.
const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = coreParameterBindings<Settings>();
  return table;
}

const Entry& entryNamed(const std::string& name) {
  for (const Entry& entry : entries()) {
    if (entry.info->name == name) return entry;
  }
  throw std::invalid_argument("unknown parameter '" + name + "'");
}

/// The core's message for a rejected value, quoting it as Python writes it.
[[noreturn]] void reject(const ParameterInfo& info, const py::handle& value, const std::string& detail = "") {
  throw std::invalid_argument(info.rejection(py::repr(value).cast<std::string>(), detail));
}

bool isInteger(const py::handle& value) { return !PyBool_Check(value.ptr()) && PyIndex_Check(value.ptr()); }

/// A whole number of any size, checked against the parameter's range before it is narrowed.
py::int_ wholeNumber(const ParameterInfo& info, const py::handle& value) {
  if (!isInteger(value)) reject(info, value, "not an integer");
  py::int_ number = py::reinterpret_steal<py::int_>(PyNumber_Index(value.ptr()));
  if (!number) throw py::error_already_set();
  double approximate = PyLong_AsDouble(number.ptr());
  if (approximate == -1.0 && PyErr_Occurred()) {  // beyond a double: compare as an infinity
    PyErr_Clear();
    const py::int_ zero(0);
    approximate = PyObject_RichCompareBool(number.ptr(), zero.ptr(), Py_LT) == 1 ? -Range::kNone : Range::kNone;
  }
  if (!info.range.contains(approximate)) reject(info, value);
  return number;
}

void assign(const ParameterInfo& info, const py::handle& value, int& field) {
  const py::int_ number = wholeNumber(info, value);
  int overflow = 0;
  const long long whole = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
  if (overflow != 0 || whole < INT_MIN || whole > INT_MAX) {
    reject(info, value, "beyond " + std::to_string(INT_MAX));
  }
  field = static_cast<int>(whole);
}

void assign(const ParameterInfo& info, const py::handle& value, std::uint64_t& field) {
  const py::int_ number = wholeNumber(info, value);
  const unsigned long long whole = PyLong_AsUnsignedLongLong(number.ptr());
  if (PyErr_Occurred()) {
    PyErr_Clear();
    reject(info, value, "beyond " + std::to_string(std::numeric_limits<std::uint64_t>::max()));
  }
  field = whole;
}

void assign(const ParameterInfo& info, const py::handle& value, double& field) {
  if (PyBool_Check(value.ptr()) || PyUnicode_Check(value.ptr()) || PyBytes_Check(value.ptr()) ||
      !PyNumber_Check(value.ptr())) {
    reject(info, value, "not a number");
  }
  const double number = PyFloat_AsDouble(value.ptr());
  if (number == -1.0 && PyErr_Occurred()) {  // a complex number, an array of several values
    PyErr_Clear();
    reject(info, value, "not a number");
  }
  field = number;  // The range is the constructor's to check, with every other parameter's.
}

void assign(const ParameterInfo& info, const py::handle& value, std::string& field) {
  if (!PyUnicode_Check(value.ptr())) reject(info, value, "not a string");
  field = value.cast<std::string>();
}

void assign(const ParameterInfo& info, const py::handle& value, WindowAlignment& field) {
  if (!PyUnicode_Check(value.ptr())) reject(info, value, "not a string");
  field = parseWindowAlignment(value.cast<std::string>());
}

py::object toPython(int value) { return py::int_(value); }
py::object toPython(std::uint64_t value) { return py::int_(value); }
py::object toPython(double value) { return py::float_(value); }
py::object toPython(const std::string& value) { return py::str(value); }
py::object toPython(WindowAlignment value) { return py::str(toString(value)); }

const char* typeName(int) { return "int"; }
const char* typeName(std::uint64_t) { return "int"; }
const char* typeName(double) { return "float"; }
const char* typeName(const std::string&) { return "str"; }
const char* typeName(WindowAlignment) { return "str"; }

}  // namespace

Settings settingsFrom(const py::dict& parameters) {
  Settings settings;
  for (const auto& [key, value] : parameters) {
    if (!PyUnicode_Check(key.ptr())) {
      throw std::invalid_argument("parameter names are strings, got " + py::repr(key).cast<std::string>());
    }
    const Entry& entry = entryNamed(key.cast<std::string>());
    std::visit([&](auto* field) { assign(*entry.info, value, *field); }, entry.field(settings));
  }
  return settings;
}

py::dict parameterValues(Settings settings, const std::string& prefix) {
  py::dict values;
  for (const Entry& entry : entries()) {
    if (entry.info->name.compare(0, prefix.size(), prefix) != 0) continue;
    std::visit([&](auto* field) { values[py::str(entry.info->name)] = toPython(*field); }, entry.field(settings));
  }
  return values;
}

py::list parameterReference() {
  py::list reference;
  Settings defaults;
  for (const Entry& entry : entries()) {
    std::visit(
        [&](auto* field) {
          py::dict row;
          row["name"] = entry.info->name;
          row["type"] = typeName(*field);
          row["default"] = toPython(*field);
          row["allowed"] = entry.info->allowed();
          row["meaning"] = entry.info->meaning;
          const std::string front_end = frontEndOwning(entry.info->name);
          row["front_end"] = front_end.empty() ? py::object(py::none()) : py::object(py::str(front_end));
          reference.append(row);
        },
        entry.field(defaults));
  }
  return reference;
}

}  // namespace python
}  // namespace mrs_vpr
