#pragma once
// JSON documents (what the CLI's --json writes) as Python objects, so a result's to_dict() has the CLI's keys.
#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace arcplan::python {

// Objects become dicts, arrays lists, numbers int or float, null None (a NaN, which JSON cannot hold, is null in the
// CLI's files too).
pybind11::object toPython(const nlohmann::json& json);

}  // namespace arcplan::python
