#include "fields.h"

#include <pybind11/stl.h>

namespace py = pybind11;

namespace movseg::python {

std::string pythonName(const std::string& name) {
  // Never destroyed: a static py::object would be released after the interpreter is gone.
  static const auto* is_keyword = new py::object(py::module_::import("keyword").attr("iskeyword"));
  return (*is_keyword)(name).cast<bool>() ? name + "_" : name;
}

std::string docOf(const std::vector<FieldInfo>& fields, const std::string& name) {
  for (const FieldInfo& field : fields) {
    if (field.name == name) return helpText(field);
  }
  return "";
}

py::array_t<double> matrixArray(const cv::Matx33d& m) {
  py::array_t<double> array({3, 3});
  auto out = array.mutable_unchecked<2>();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = m(r, c);
  }
  return array;
}

namespace {

const char* pythonType(FieldType type) {
  switch (type) {
    case FieldType::kBool: return "bool";
    case FieldType::kInt:
    case FieldType::kUnsigned: return "int";
    case FieldType::kReal: return "float";
    case FieldType::kChoice: return "str";
    case FieldType::kMatrix: break;
  }
  return "matrix";
}

}  // namespace

pybind11::list fieldTable(const std::vector<FieldInfo>& fields) {
  py::list table;
  for (const FieldInfo& field : fields) {
    table.append(py::dict(py::arg("name") = pythonName(field.name),
                          py::arg("type") = pythonType(field.type),
                          py::arg("choices") = field.choices, py::arg("doc") = helpText(field)));
  }
  return table;
}

std::string reprOf(const py::object& object, const std::string& type,
                   const std::vector<FieldInfo>& fields) {
  std::string text = "movseg." + type + "(";
  for (const FieldInfo& field : fields) {
    py::object value = object.attr(pythonName(field.name).c_str());
    if (py::isinstance<py::array>(value)) value = value.attr("tolist")();
    text += "\n    " + pythonName(field.name) + "=" + py::repr(value).cast<std::string>() + ",";
  }
  return text + "\n)";
}

}  // namespace movseg::python
