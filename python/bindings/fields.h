// Python attributes generated from movseg's field tables (movseg/params.def,
// movseg/diagnostics.def): one property per field, named as in C++ (a Python keyword gets a
// trailing underscore: lambda_), documented by the table's help text; enums are their names.
#pragma once

#include <string>
#include <type_traits>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "movseg/fields.h"

namespace movseg::python {

// `lambda` -> `lambda_`.
std::string pythonName(const std::string& name);

// The table's help text of the field `name` in `fields`.
std::string docOf(const std::vector<FieldInfo>& fields, const std::string& name);

// A 3x3 float64 array.
pybind11::array_t<double> matrixArray(const cv::Matx33d& m);

// A field's value as the Python object its attribute gives.
template <typename T>
pybind11::object toPython(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    return pybind11::str(enumNames<T>()[static_cast<std::size_t>(value)]);
  } else if constexpr (std::is_same_v<T, cv::Matx33d>) {
    return matrixArray(value);
  } else {
    return pybind11::cast(value);
  }
}

// The table as a list of dicts {name (Python's), type ("bool", "int", "float", "str" or
// "matrix"), choices, doc}, for python/tools/stubgen.py.
pybind11::list fieldTable(const std::vector<FieldInfo>& fields);

// "movseg.Name(\n    field=repr,\n    ...)" over every field of the table, one per line.
std::string reprOf(const pybind11::object& object, const std::string& type,
                   const std::vector<FieldInfo>& fields);

}  // namespace movseg::python
