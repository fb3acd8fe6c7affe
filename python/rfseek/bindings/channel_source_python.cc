/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(channel_source.h) */
/* BINDTOOL_HEADER_FILE_HASH(da58fd6efa9078e131ce12f97fa8dacf) */

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
             py::arg("speedup") = 1.0,
             py::arg("follow_truth") = false,
             "\\param sc the run's scenario (validated; bad fields raise "
             "ValueError) \\param mode \"burst\" or \"continuous\" \\param "
             "lockstep wait for the cmd of each slot before producing the next \\param "
             "realtime pace output to real time (for live-looking demos) \\param speedup "
             "pacing speed-up over real time, in (0, 1e6] (1: real time) \\param "
             "follow_truth follow the true state on 'truth' (a vehicle flown by SITL)")
        .def("config", &channel_source::config, "The scenario it simulates.")
        .def("mode", &channel_source::mode, "'burst' or 'continuous'.")
        .def("slot",
             &channel_source::slot,
             "Current slot index (the slot being, or last, produced).")
        .def("malformed_count",
             &channel_source::malformed_count,
             "cmd messages dropped as malformed.")
        .def("stale_count",
             &channel_source::stale_count,
             "cmd messages ignored as stale. In lockstep: a slot other than the current "
             "one. Free-running: a slot older than the newest command applied, or one "
             "not flown yet.")
        .def("late_count",
             &channel_source::late_count,
             "Free-running: commands applied after their slot had passed (the latest one "
             "wins).")
        .def("lockstep",
             &channel_source::lockstep,
             "Waits for each slot's cmd before producing the next.")
        .def("realtime",
             &channel_source::realtime,
             "Paces its output to the sample clock.")
        .def("speedup", &channel_source::speedup, "Pacing speed-up over real time.")
        .def("follow_truth",
             &channel_source::follow_truth,
             "The world follows the truth on 'truth' (a vehicle flown by SITL).")
        .def("truth_count",
             &channel_source::truth_count,
             "follow_truth: truths received and kept.")
        .def("truth_dropped_count",
             &channel_source::truth_dropped_count,
             "follow_truth: truths dropped (malformed, or before the last one).")
        .def("set_snr_db",
             &channel_source::set_snr_db,
             py::arg("snr_db"),
             "Change the SNR at the initial distance from now on (dB).")
        .def("set_heading_noise_rad",
             &channel_source::set_heading_noise_rad,
             py::arg("sigma"),
             "Change the heading sensor's noise std from now on (rad).")
        .def("set_turn_rate_rad_per_s",
             &channel_source::set_turn_rate_rad_per_s,
             py::arg("rate"),
             "Change the turn-rate limit from now on (rad/s; 0: instantaneous).")
        .def("set_lockstep",
             &channel_source::set_lockstep,
             py::arg("lockstep"),
             "Wait, or not, for each slot's cmd.")
        .def("set_realtime",
             &channel_source::set_realtime,
             py::arg("realtime"),
             "Pace, or not, to the sample clock.")
        .def("set_speedup",
             &channel_source::set_speedup,
             py::arg("speedup"),
             "Raises ValueError outside (0, 1e6].");
}
