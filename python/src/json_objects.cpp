#include "json_objects.h"

#include <cmath>

namespace py = pybind11;

namespace arcplan::python {

py::object toPython(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (const auto& [key, value] : json.items()) dict[py::str(key)] = toPython(value);
      return std::move(dict);
    }
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const auto& value : json) list.append(toPython(value));
      return std::move(list);
    }
    case nlohmann::json::value_t::string:
      return py::str(json.get_ref<const std::string&>());
    case nlohmann::json::value_t::boolean:
      return py::bool_(json.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(json.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(json.get<unsigned long long>());
    case nlohmann::json::value_t::number_float: {
      const double value = json.get<double>();
      return std::isfinite(value) ? py::object(py::float_(value)) : py::object(py::none());
    }
    default:
      return py::none();
  }
}

}  // namespace arcplan::python
