#pragma once
// The Python objects of the model loop (arcplan.model), shared by bind_model.cpp (loading, the loop's functions) and
// bind_model_results.cpp (result classes). A result keeps the data it was computed on, so its arrays (measured,
// predicted, residual) can be produced when asked for.
#include <memory>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "arcplan/model/compare.h"
#include "arcplan/model/diagnose.h"
#include "arcplan/model/workflow.h"
#include "json_objects.h"

namespace arcplan::python {

// Loaded data (the fit log and the optional validation log), shared by every result made from it.
using DataPointer = std::shared_ptr<model::LoadedData>;

// A fitted model with the data it was fitted on.
struct FittedOnData {
  model::FittedModel model;
  DataPointer data;
};

struct ComparisonResult {
  model::Comparison comparison;
  std::shared_ptr<const FittedOnData> fitted;
};

struct FitResult {
  model::FitStep step;
  DataPointer data;
};

// The error after every step of the loop, in memory (or read from a session folder's session.json).
struct History {
  std::vector<model::SessionStep> steps;
};

void bindModelResults(pybind11::module_& module);

}  // namespace arcplan::python
