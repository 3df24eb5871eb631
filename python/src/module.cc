// The extension module probrobscene._core: the C++ engine behind the Python package. The
// package's __init__.py wraps it with the documented API (load, loads, ScenarioError, ...).
#include "bindings.h"

PYBIND11_MODULE(_core, m) {
  m.doc() = "The ProbRobScene engine (internal; use the probrobscene package).";
  prs::python::BindScene(m);
  prs::python::BindScenario(m);
  prs::python::BindSearch(m);
  prs::python::BindCampaign(m);
  prs::python::BindReplay(m);
  prs::python::BindDataset(m);
}
