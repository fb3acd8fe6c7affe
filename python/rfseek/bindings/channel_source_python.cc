/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(channel_source.h) */
/* BINDTOOL_HEADER_FILE_HASH(77079a1adca4e199a465ae2330180c18) */

#include <gr-rfseek/channel_source.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_channel_source(py::module& m)
{
    using gr::rfseek::channel_source;
    py::class_<channel_source,
               gr::sync_block,
               gr::block,
               gr::basic_block,
               std::shared_ptr<channel_source>>(
        m,
        "channel_source",
        "Simulated beacon as received by the UAV (complex64 out; 'cmd' in, 'state' out).")
        .def(py::init(&channel_source::make),
             py::arg("scenario"),
             py::arg("mode") = "burst",
             py::arg("lockstep") = true,
             py::arg("realtime") = false,
             py::arg("speedup") = 1.0)
        .def("config", &channel_source::config)
        .def("mode", &channel_source::mode)
        .def("slot", &channel_source::slot)
        .def("malformed_count", &channel_source::malformed_count)
        .def("stale_count", &channel_source::stale_count)
        .def("late_count", &channel_source::late_count)
        .def("lockstep", &channel_source::lockstep)
        .def("realtime", &channel_source::realtime)
        .def("speedup", &channel_source::speedup)
        .def("set_snr_db", &channel_source::set_snr_db, py::arg("snr_db"))
        .def("set_heading_noise_rad",
             &channel_source::set_heading_noise_rad,
             py::arg("sigma"))
        .def("set_turn_rate_rad_per_s",
             &channel_source::set_turn_rate_rad_per_s,
             py::arg("rate"))
        .def("set_lockstep", &channel_source::set_lockstep, py::arg("lockstep"))
        .def("set_realtime", &channel_source::set_realtime, py::arg("realtime"))
        .def("set_speedup", &channel_source::set_speedup, py::arg("speedup"));
}
