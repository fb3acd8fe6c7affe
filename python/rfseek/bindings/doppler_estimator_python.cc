/*
 * Copyright 2026 gr-rfseek authors.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */

/* BINDTOOL_HEADER_FILE(doppler_estimator.h) */
/* BINDTOOL_HEADER_FILE_HASH(6b3ef3305c8b70d0c5ff4032dfd9f521) */

#include <gr-rfseek/doppler_estimator.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

void bind_doppler_estimator(py::module& m)
{
    using gr::rfseek::doppler_estimator;
    py::class_<doppler_estimator,
               gr::sync_block,
               gr::block,
               gr::basic_block,
               std::shared_ptr<doppler_estimator>>(
        m,
        "doppler_estimator",
        "Windowed, zero-padded FFT frequency estimator: one 'meas' message per window.")
        .def(py::init(&doppler_estimator::make),
             py::arg("samp_rate"),
             py::arg("window_len"),
             py::arg("fft_len"),
             py::arg("window") = "rectangular",
             py::arg("interpolator") = "parabolic",
             py::arg("alignment") = "tag",
             py::arg("tag_key") = "rfseek_beacon",
             py::arg("period") = 0,
             py::arg("offset") = 0,
             py::arg("min_freq") = 0.0,
             py::arg("max_freq") = 0.0,
             py::arg("threshold_db") = 2.0)
        .def("window", &doppler_estimator::window)
        .def("interpolator", &doppler_estimator::interpolator)
        .def("alignment", &doppler_estimator::alignment)
        .def("min_freq", &doppler_estimator::min_freq)
        .def("max_freq", &doppler_estimator::max_freq)
        .def("window_count", &doppler_estimator::window_count)
        .def("invalid_count", &doppler_estimator::invalid_count)
        .def("truncated_count", &doppler_estimator::truncated_count)
        .def("set_window", &doppler_estimator::set_window, py::arg("window"))
        .def("set_interpolator",
             &doppler_estimator::set_interpolator,
             py::arg("interpolator"))
        .def("threshold_db", &doppler_estimator::threshold_db)
        .def("set_threshold_db",
             &doppler_estimator::set_threshold_db,
             py::arg("threshold_db"))
        .def("set_band",
             &doppler_estimator::set_band,
             py::arg("min_freq"),
             py::arg("max_freq"));
}
