/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(study.h) */
/* BINDTOOL_HEADER_FILE_HASH(d064e2e3f9bf9e047325fd2069bc5436) */

#include <gr-rfseek/study.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_study(py::module& m)
{
    using namespace gr::rfseek;
    py::class_<study_point>(
        m,
        "study_point",
        "One point of a Monte Carlo study: preset, then the given (key, value) settings "
        "in "
        "order, then the sweep value. run(strategy, seed) is one row, as "
        "rfseek-montecarlo computes it with any backend.")
        .def(py::init<const std::string&,
                      const study_point::kv_list&,
                      const std::string&,
                      const std::string&>(),
             py::arg("preset") = "",
             py::arg("given") = study_point::kv_list{},
             py::arg("sweep_key") = "",
             py::arg("sweep_value") = "")
        .def("validate", &study_point::validate, py::arg("strategies"))
        .def("seeker", &study_point::seeker, py::arg("strategy"), py::arg("seed"))
        .def("run",
             &study_point::run,
             py::arg("strategy"),
             py::arg("seed"),
             py::call_guard<py::gil_scoped_release>())
        .def_property_readonly("preset", &study_point::preset)
        .def_property_readonly("sweep_key", &study_point::sweep_key)
        .def_property_readonly("sweep_value", &study_point::sweep_value)
        .def_property_readonly("given", &study_point::given)
        .def_property_readonly("scenario", &study_point::scenario_config)
        .def_property_readonly("seeker_sets", &study_point::seeker_sets)
        .def_property_readonly("estimator", &study_point::estimator)
        .def_static("is_key", &study_point::is_key, py::arg("key"));
}
