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
             py::arg("sweep_value") = "",
             "One configuration of a study: a preset, settings (key, value) in order, "
             "and a sweep key and value; ValueError for an unknown key or value.")
        .def("validate",
             &study_point::validate,
             py::arg("strategies"),
             "Ranges of the scenario and of each strategy's configuration (throws, "
             "naming it).")
        .def("seeker",
             &study_point::seeker,
             py::arg("strategy"),
             py::arg("seed"),
             "The seeker configuration of one run: seeker_for(scenario with seed), then "
             "the seeker constants given.")
        .def("run",
             &study_point::run,
             py::arg("strategy"),
             py::arg("seed"),
             py::call_guard<py::gil_scoped_release>(),
             "One run of the closed loop, scenario seed = seed (no records kept).")
        .def_property_readonly(
            "preset", &study_point::preset, "The preset's name ('' for none).")
        .def_property_readonly(
            "sweep_key", &study_point::sweep_key, "The swept key ('' for none).")
        .def_property_readonly(
            "sweep_value", &study_point::sweep_value, "The swept value.")
        .def_property_readonly("given", &study_point::given, "The settings, as given.")
        .def_property_readonly(
            "scenario", &study_point::scenario_config, "The scenario the settings make.")
        .def_property_readonly("seeker_sets",
                               &study_point::seeker_sets,
                               "The settings that are seeker constants.")
        .def_property_readonly(
            "estimator", &study_point::estimator, "The estimator settings.")
        .def_static("is_key",
                    &study_point::is_key,
                    py::arg("key"),
                    "Whether key is a setting a study point accepts.");
}
