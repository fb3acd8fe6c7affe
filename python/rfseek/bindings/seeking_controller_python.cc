/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(seeking_controller.h) */
/* BINDTOOL_HEADER_FILE_HASH(ce298c2a46b6419f60bdb89beba45764) */

#include <gr-rfseek/seeking_controller.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_seeking_controller(py::module& m)
{
    using gr::rfseek::seeking_controller;
    py::class_<seeking_controller,
               gr::block,
               gr::basic_block,
               std::shared_ptr<seeking_controller>>(
        m,
        "seeking_controller",
        "The seeker as a message block: 'meas', 'nav' in; 'cmd', 'telemetry' out.")
        .def(
            py::init(&seeking_controller::make),
            py::arg("config"),
            "\\param cfg strategy and constants (validated; bad fields raise ValueError)")
        .def("config", &seeking_controller::config, "The seeker configuration it runs.")
        .def("stage", &seeking_controller::stage, "The seeker's current stage.")
        .def("theta_est",
             &seeking_controller::theta_est,
             "The seeker's current bearing estimate (rad).")
        .def("updates", &seeking_controller::updates, "Heading updates applied so far.")
        .def("meas_count", &seeking_controller::meas_count, "meas messages received.")
        .def("invalid_count",
             &seeking_controller::invalid_count,
             "meas messages flagged invalid (ignored by the strategy).")
        .def("malformed_count",
             &seeking_controller::malformed_count,
             "Messages dropped as malformed.")
        .def("status", &seeking_controller::status, "0 seeking, 1 arrived, 2 located")
        .def("location", &seeking_controller::location, "the latest fix")
        .def("done",
             &seeking_controller::done,
             "self arrival: the mission is over (located, or given up)")
        .def("set_wait_for_heading",
             &seeking_controller::set_wait_for_heading,
             py::arg("wait"),
             "Wait for the vehicle's first heading (meas tag or nav report) before "
             "seeking; until then each meas is counted and gets no cmd.")
        .def("wait_for_heading",
             &seeking_controller::wait_for_heading,
             "Whether it waits for the first heading before seeking.")
        .def("waiting_count",
             &seeking_controller::waiting_count,
             "meas messages set aside while waiting for the first heading.")
        .def("unpaired_count",
             &seeking_controller::unpaired_count,
             "Windows with no nav report within 1 s of their time (measured without a "
             "heading).")
        .def("set_wind_forecast",
             &seeking_controller::set_wind_forecast,
             py::arg("east_mps"),
             py::arg("north_mps"),
             "A new wind forecast for the ground track, mid-flight (m/s toward east and "
             "north, compass frame; both 0: none); it replaces what the law had learned. "
             "False, nothing changed, for a non-finite value or a speed not below the "
             "airspeed (logged as an error: a GUI callback must not stop a flight) or a "
             "strategy without a ground track.");
}
